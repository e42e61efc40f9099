// expect: 4 x the reference (= 4) everywhere
// mistake: the factor 4 is missing from the denominator
vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)
{
    vec3 H = halfwayVector(L, V);
    float D = distributionGGX(N, H, roughness);
    float G = geometrySmith(N, V, L, roughness);
    vec3 F = fresnelSchlick(max(dot(H, V), 0.0), F0);
    return D * G * F / max(max(dot(N, V), 0.0) * max(dot(N, L), 0.0), 1e-4);
}
