// expect: N.L in the denominator 4 N.L N.V missing
// The denominator keeps N.V only.
vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)
{
    vec3 H = halfwayVector(L, V);
    float nv = max(dot(N, V), 0.0);
    vec3 numerator = distributionGGX(N, H, roughness) * geometrySmith(N, V, L, roughness) *
                     fresnelSchlick(max(dot(H, V), 0.0), F0);
    return numerator / max(4.0 * nv, 1e-4);
}
