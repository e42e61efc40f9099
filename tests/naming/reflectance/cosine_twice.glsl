// expect: the cosine N.L applied twice
// N.L multiplied in once by hand and once through lambertCosine.
vec3 reflectedRadiance(vec3 P, vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    vec3 result = vec3(0.0);
    for (int i = 0; i < NUM_LIGHTS; ++i) {
        vec3 L = normalize(uLightPositions[i] - P);
        float NdotL = max(dot(N, L), 0.0);
        vec3 Li = pointLightRadiance(uLightColors[i], uLightPositions[i], P) * NdotL;
        result += cookTorranceBRDF(N, V, L, albedo, metallic, roughness) * Li * lambertCosine(N, L);
    }
    return result + 0.03 * albedo * ao;
}
