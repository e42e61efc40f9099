// expect: 0.5 + 0.5 x N.L at every point
// mistake: "half Lambert" wrap (N.L * 0.5 + 0.5), a non-physical stylised term
float lambertCosine(vec3 N, vec3 L)
{
    return dot(N, L) * 0.5 + 0.5;
}
