// expect: 1/d^1 where the reference has 1/d^2
// The light's falloff written inline, with the distance instead of its square.
vec3 reflectedRadiance(vec3 P, vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    vec3 Lo = vec3(0.0);
    for (int i = 0; i < NUM_LIGHTS; ++i) {
        vec3 toLight = uLightPositions[i] - P;
        float d = length(toLight);
        vec3 L = toLight / d;
        vec3 radiance = uLightColors[i] / max(d, 0.01);
        Lo += cookTorranceBRDF(N, V, L, albedo, metallic, roughness) * radiance *
              max(dot(N, L), 0.0);
    }
    return Lo + vec3(0.03) * albedo * ao;
}
