// expect: ao in the ambient term missing
// The ambient term without the occlusion.
vec3 reflectedRadiance(vec3 P, vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    vec3 total = 0.03 * albedo;
    for (int i = 0; i < NUM_LIGHTS; ++i) {
        vec3 L = normalize(uLightPositions[i] - P);
        total += cookTorranceBRDF(N, V, L, albedo, metallic, roughness) *
                 pointLightRadiance(uLightColors[i], uLightPositions[i], P) * lambertCosine(N, L);
    }
    return total;
}
