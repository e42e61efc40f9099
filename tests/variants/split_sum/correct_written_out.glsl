// correct: Fresnel-roughness and reflect written out by hand (products instead of pow),
// clamp instead of max
vec3 ambientIBL(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    float NdotV = clamp(dot(N, V), 0.0, 1.0);
    vec3 R = 2.0 * dot(N, V) * N - V;
    vec3 F0 = mix(vec3(0.04), albedo, metallic);
    float m = 1.0 - NdotV;
    float m5 = m * m * m * m * m;
    vec3 F = F0 + (max(vec3(1.0 - roughness), F0) - F0) * m5;
    vec3 kS = F;
    vec3 kD = (vec3(1.0) - kS) * (1.0 - metallic);
    vec3 irradiance = texture(uIrradianceMap, N).rgb;
    vec3 prefiltered = textureLod(uPrefilterMap, R, roughness * uPrefilterMaxLod).rgb;
    vec2 brdf = texture(uBrdfLut, vec2(NdotV, roughness)).rg;
    vec3 specular = prefiltered * (F0 * brdf.x + brdf.y);
    return (kD * irradiance * albedo + specular) * ao;
}
