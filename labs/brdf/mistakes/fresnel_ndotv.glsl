// expect: F evaluated at N.V, where the specular lobe has H.V
// mistake: Fresnel fed N.V instead of H.V (inline specular and kD both use it)
vec3 cookTorranceBRDF(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 H = halfwayVector(L, V);
    float NdotV = max(dot(N, V), 0.0);
    float NdotL = max(dot(N, L), 0.0);
    vec3 F = fresnelSchlick(NdotV, F0);
    float DG = distributionGGX(N, H, roughness) * geometrySmith(N, V, L, roughness);
    vec3 specular = DG * F / max(4.0 * NdotV * NdotL, 1e-4);
    vec3 kD = (vec3(1.0) - F) * (1.0 - metallic);
    return kD * albedo / PI + specular;
}
