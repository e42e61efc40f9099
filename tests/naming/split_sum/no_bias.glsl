// expect: without the LUT's bias B
// Only the LUT's scale: the specular part prefiltered * F0 * A.
vec3 ambientIBL(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    float NdotV = max(dot(N, V), 0.0);
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 kD = (1.0 - fresnelSchlickRoughness(NdotV, F0, roughness)) * (1.0 - metallic);
    vec3 diffuse = kD * albedo * textureLod(uIrradianceMap, N, 0.0).rgb;
    float A = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).r;
    vec3 R = reflect(-V, N);
    vec3 specular = textureLod(uPrefilterMap, R, roughness * uPrefilterMaxLod).rgb * F0 * A;
    return ao * (diffuse + specular);
}
