// correct: floor 1e-3 on the denominator, clamp instead of max
vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)
{
    vec3 H = halfwayVector(L, V);
    float NdotV = clamp(dot(N, V), 0.0, 1.0);
    float NdotL = clamp(dot(N, L), 0.0, 1.0);
    vec3 F = fresnelSchlick(clamp(dot(H, V), 0.0, 1.0), F0);
    float DG = distributionGGX(N, H, roughness) * geometrySmith(N, V, L, roughness);
    return DG * F / max(4.0 * NdotV * NdotL, 1e-3);
}
