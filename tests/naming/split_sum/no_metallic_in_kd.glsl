// expect: (1 - metallic) in kD missing
// kD = 1 - F: metals keep a diffuse part.
vec3 ambientIBL(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    float NdotV = max(dot(N, V), 0.0);
    vec3 F0 = mix(vec3(0.04), albedo, metallic);
    vec3 kS = fresnelSchlickRoughness(NdotV, F0, roughness);
    vec3 kD = vec3(1.0) - kS;
    vec3 diffuse = textureLod(uIrradianceMap, N, 0.0).rgb * albedo;
    vec3 prefiltered = textureLod(uPrefilterMap, reflect(-V, N), roughness * uPrefilterMaxLod).rgb;
    vec2 brdf = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).rg;
    return (kD * diffuse + prefiltered * (F0 * brdf.x + brdf.y)) * ao;
}
