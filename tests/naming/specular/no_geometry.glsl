// expect: the geometry term G missing
// The shadowing-masking term left out.
vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)
{
    vec3 H = normalize(V + L);
    float NdotV = max(dot(N, V), 0.0);
    float NdotL = max(dot(N, L), 0.0);
    vec3 fresnel = fresnelSchlick(max(dot(V, H), 0.0), F0);
    float ndf = distributionGGX(N, H, roughness);
    return ndf * fresnel / max(4.0 * NdotV * NdotL, 1e-4);
}
