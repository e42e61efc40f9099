// expect: fits the reference without N.L
// mistake: the cosine factor N.L of the reflectance equation is missing
vec3 reflectedRadiance(vec3 P, vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    vec3 Lo = vec3(0.0);
    for (int i = 0; i < NUM_LIGHTS; ++i) {
        vec3 L = normalize(uLightPositions[i] - P);
        vec3 radiance = pointLightRadiance(uLightColors[i], uLightPositions[i], P);
        Lo += cookTorranceBRDF(N, V, L, albedo, metallic, roughness) * radiance;
    }
    return Lo + 0.03 * albedo * ao;
}
