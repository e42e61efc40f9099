// correct: Fresnel fed H.L, which equals H.V because H bisects L and V
vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)
{
    vec3 H = halfwayVector(L, V);
    vec3 F = fresnelSchlick(max(dot(H, L), 0.0), F0);
    float denom = max(4.0 * max(dot(N, L), 0.0) * max(dot(N, V), 0.0), 1e-4);
    return F * (distributionGGX(N, H, roughness) * geometrySmith(N, V, L, roughness) / denom);
}
