// expect: a guard for negative N.L missing
// mistake: no clamp on N.L, light from below the surface subtracts energy
float lambertCosine(vec3 N, vec3 L)
{
    return dot(N, L);
}
