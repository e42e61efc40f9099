// expect: the reference divided by G1(N.L)
// mistake: Smith with only one G1 (masking towards V, shadowing towards L forgotten)
float geometrySmith(vec3 N, vec3 V, vec3 L, float roughness)
{
    return geometrySchlickGGX(max(dot(N, V), 0.0), roughness);
}
