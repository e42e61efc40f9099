// expect: is ao missing
// The ambient occlusion never applied.
vec3 ambientIBL(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    float cosV = max(dot(N, V), 0.0);
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 F = fresnelSchlickRoughness(cosV, F0, roughness);
    vec3 diffuseLight = texture(uIrradianceMap, N).rgb * albedo * (1.0 - F) * (1.0 - metallic);
    vec2 scaleBias = texture(uBrdfLut, vec2(cosV, roughness)).rg;
    vec3 specularLight = textureLod(uPrefilterMap, reflect(-V, N), roughness * uPrefilterMaxLod).rgb *
                         (F0 * scaleBias.x + scaleBias.y);
    return diffuseLight + specularLight;
}
