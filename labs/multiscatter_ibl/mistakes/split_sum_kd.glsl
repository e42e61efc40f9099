// expect: split_sum's kD
// mistake: kD = (1 - F)(1 - metallic) as in split_sum: the light given back by multiple scattering is counted twice, once reflected and once diffused
vec3 ambientIBLMultiscatter(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    float NdotV = max(dot(N, V), 0.0);
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec2 AB = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).rg;
    vec3 F = fresnelSchlickRoughness(NdotV, F0, roughness);
    vec3 FssEss = F * AB.x + AB.y;
    float Ems = 1.0 - (AB.x + AB.y);
    vec3 Favg = F0 + (1.0 - F0) / 21.0;
    vec3 Fms = FssEss * Favg / (1.0 - Ems * Favg);
    vec3 kD = albedo * (1.0 - metallic) * (1.0 - F);
    vec3 irradiance = textureLod(uIrradianceMap, N, 0.0).rgb;
    vec3 prefiltered = textureLod(uPrefilterMap, reflect(-V, N), roughness * uPrefilterMaxLod).rgb;
    return (FssEss * prefiltered + (Fms * Ems + kD) * irradiance) * ao;
}
