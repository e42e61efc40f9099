// expect: fits no falloff with distance where the reference has 1/d^2
// mistake: the light colour used as incoming radiance, without the inverse-square falloff
vec3 reflectedRadiance(vec3 P, vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    vec3 Lo = vec3(0.0);
    for (int i = 0; i < NUM_LIGHTS; ++i) {
        vec3 L = normalize(uLightPositions[i] - P);
        Lo += cookTorranceBRDF(N, V, L, albedo, metallic, roughness) * uLightColors[i] *
              lambertCosine(N, L);
    }
    return Lo + 0.03 * albedo * ao;
}
