// mistake: the lesson's four lights written into the loop instead of NUM_LIGHTS (the scenes
// with 1, 3 and 4 lights cannot tell: the lights past the scene's last read as black)
// expect: ignores light 5 and up: right with NUM_LIGHTS up to 4, wrong from 5
vec3 reflectedRadiance(vec3 P, vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    vec3 Lo = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        vec3 L = normalize(uLightPositions[i] - P);
        vec3 radiance = pointLightRadiance(uLightColors[i], uLightPositions[i], P);
        Lo += cookTorranceBRDF(N, V, L, albedo, metallic, roughness) * radiance *
              lambertCosine(N, L);
    }
    return Lo + 0.03 * albedo * ao;
}
