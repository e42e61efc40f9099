// expect: prefiltered map where the irradiance belongs
// mistake: the multiple-scattering term lit by the prefiltered map: light that bounced many times has forgotten its direction, so the irradiance lights it
vec3 ambientIBLMultiscatter(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    float NdotV = max(dot(N, V), 0.0);
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec2 AB = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).rg;
    vec3 FssEss = fresnelSchlickRoughness(NdotV, F0, roughness) * AB.x + AB.y;
    float Ems = 1.0 - (AB.x + AB.y);
    vec3 Favg = F0 + (1.0 - F0) / 21.0;
    vec3 Fms = FssEss * Favg / (1.0 - Ems * Favg);
    vec3 kD = albedo * (1.0 - metallic) * (1.0 - (FssEss + Fms * Ems));
    vec3 irradiance = textureLod(uIrradianceMap, N, 0.0).rgb;
    vec3 prefiltered = textureLod(uPrefilterMap, reflect(-V, N), roughness * uPrefilterMaxLod).rgb;
    return ((FssEss + Fms * Ems) * prefiltered + kD * irradiance) * ao;
}
