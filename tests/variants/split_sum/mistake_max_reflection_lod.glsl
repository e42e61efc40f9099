// mistake: LearnOpenGL's const float MAX_REFLECTION_LOD = 4.0 instead of uPrefilterMaxLod (the
// same value with the default maps' five mips; the host makes other mip counts)
// expect: hard-coded host value (uPrefilterMaxLod)
vec3 ambientIBL(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    const float MAX_REFLECTION_LOD = 4.0;
    float NdotV = max(dot(N, V), 0.0);
    vec3 R = reflect(-V, N);
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 F = fresnelSchlickRoughness(NdotV, F0, roughness);
    vec3 kD = (1.0 - F) * (1.0 - metallic);
    vec3 diffuse = albedo * texture(uIrradianceMap, N).rgb;
    vec3 prefiltered = textureLod(uPrefilterMap, R, roughness * MAX_REFLECTION_LOD).rgb;
    vec2 AB = texture(uBrdfLut, vec2(NdotV, roughness)).rg;
    vec3 specular = prefiltered * (F0 * AB.x + AB.y);
    return (kD * diffuse + specular) * ao;
}
