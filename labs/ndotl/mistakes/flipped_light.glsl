// expect: -L in place of L
// mistake: light vector taken pointing from the light to the surface (-L)
float lambertCosine(vec3 N, vec3 L)
{
    return max(dot(N, -L), 0.0);
}
