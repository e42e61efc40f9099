// The reflectance equation for point lights: the integral over incoming directions collapses
// to a sum, one term per light, of BRDF x incoming radiance x cosine. A constant ambient term
// (0.03 albedo ao) stands in for the environment light that is not modelled yet.
vec3 reflectedRadiance(vec3 P, vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    // BEGIN SOLUTION
    vec3 Lo = vec3(0.0);
    for (int i = 0; i < NUM_LIGHTS; ++i) {
        vec3 L = pbrlab_safeNormalize(uLightPositions[i] - P, vec3(0.0));
        vec3 radiance = pointLightRadiance(uLightColors[i], uLightPositions[i], P);
        Lo += cookTorranceBRDF(N, V, L, albedo, metallic, roughness) * radiance *
              lambertCosine(N, L);
    }
    return Lo + 0.03 * albedo * ao;
    // END SOLUTION
}
