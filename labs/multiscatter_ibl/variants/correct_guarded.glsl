// A correct variant: Ess computed first, the series' denominator guarded against 0 (it is
// at least Ess >= 0.3 over the LUT), the energy left to the diffuse layer named.
vec3 ambientIBLMultiscatter(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    float NdotV = clamp(dot(N, V), 0.0, 1.0);
    vec2 lut = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).rg;
    float Ess = lut.x + lut.y;
    float Ems = 1.0 - Ess;
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 kS = F0 + (max(vec3(1.0 - roughness), F0) - F0) * pow(1.0 - NdotV, 5.0);
    vec3 singleScattering = kS * lut.x + lut.y;
    vec3 Favg = F0 + (vec3(1.0) - F0) / 21.0;
    vec3 multipleScattering = singleScattering * Favg * Ems / max(vec3(1.0) - Ems * Favg, 1e-4);
    vec3 energyLeft = vec3(1.0) - singleScattering - multipleScattering;
    vec3 diffuse = albedo * (1.0 - metallic) * energyLeft;
    vec3 irradiance = textureLod(uIrradianceMap, N, 0.0).rgb;
    vec3 prefiltered = textureLod(uPrefilterMap, reflect(-V, N), roughness * uPrefilterMaxLod).rgb;
    return (singleScattering * prefiltered + (multipleScattering + diffuse) * irradiance) * ao;
}
