// expect: wrong only where N.L < 0
// mistake: abs(N.L) lights the surface from both sides
float lambertCosine(vec3 N, vec3 L)
{
    return abs(dot(N, L));
}
