// correct: composed from the contract functions, own guard on the light direction
vec3 reflectedRadiance(vec3 P, vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    vec3 sum = vec3(0.0);
    for (int i = 0; i < NUM_LIGHTS; i++) {
        vec3 toLight = uLightPositions[i] - P;
        float len = length(toLight);
        vec3 L = len > 1e-6 ? toLight / len : vec3(0.0);
        float cosine = clamp(dot(N, L), 0.0, 1.0);
        vec3 Li = pointLightRadiance(uLightColors[i], uLightPositions[i], P);
        sum += cookTorranceBRDF(N, V, L, albedo, metallic, roughness) * (Li * cosine);
    }
    return sum + albedo * (0.03 * ao);
}
