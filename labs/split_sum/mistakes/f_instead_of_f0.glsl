// expect: fits the reference with F where the bracket has F0
// mistake: prefiltered * (F * A + B): Fresnel applied twice (the LUT already holds it)
vec3 ambientIBL(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    float NdotV = max(dot(N, V), 0.0);
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 F = fresnelSchlickRoughness(NdotV, F0, roughness);
    vec3 kD = (1.0 - F) * (1.0 - metallic);
    vec3 diffuse = albedo * textureLod(uIrradianceMap, N, 0.0).rgb;
    vec3 prefiltered = textureLod(uPrefilterMap, reflect(-V, N), roughness * uPrefilterMaxLod).rgb;
    vec2 AB = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).rg;
    return (kD * diffuse + prefiltered * (F * AB.x + AB.y)) * ao;
}
