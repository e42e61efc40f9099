// expect: -L in place of L
// mistake: L points from the light to the surface (P - lightPos) instead of towards the light
vec3 reflectedRadiance(vec3 P, vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    vec3 Lo = vec3(0.0);
    for (int i = 0; i < NUM_LIGHTS; ++i) {
        vec3 L = normalize(P - uLightPositions[i]);
        vec3 radiance = pointLightRadiance(uLightColors[i], uLightPositions[i], P);
        Lo += cookTorranceBRDF(N, V, L, albedo, metallic, roughness) * radiance *
              lambertCosine(N, L);
    }
    return Lo + 0.03 * albedo * ao;
}
