// Ambient light that keeps the energy single scattering loses (Fdez-Aguera 2019, "A
// Multiple-Scattering Microfacet Model for Real-Time Image-based Lighting", JCGT 8(1)).
// The split sum's specular part reflects FssEss = kS A + B of white light, kS the roughness-
// aware Fresnel; with F0 = 1 that is Ess = A + B, the directional albedo of step `furnace`,
// and Ems = 1 - Ess is what bounced more than once between microfacets and was dropped.
// Multiple scattering returns it: each further bounce keeps the fraction F_avg of the light
// (F_avg = F0 + (1 - F0) / 21, the hemispherical average of Schlick's Fresnel) and a share Ems
// of it scatters again, so the series sums to
//     Fms = FssEss F_avg / (1 - Ems F_avg),
// reflected as Fms Ems of the (cosine-weighted) irradiance: after many bounces the light has
// forgotten its direction. What neither reflects enters the diffuse layer:
//     kD = albedo (1 - metallic) (1 - (FssEss + Fms Ems)).
// Result: (FssEss prefiltered + (Fms Ems + kD) irradiance) ao.
vec3 ambientIBLMultiscatter(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    // BEGIN SOLUTION
    float NdotV = max(dot(N, V), 0.0);
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec2 AB = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).rg;
    vec3 kS = fresnelSchlickRoughness(NdotV, F0, roughness);
    vec3 FssEss = kS * AB.x + AB.y;
    float Ess = AB.x + AB.y;
    float Ems = 1.0 - Ess;
    vec3 Favg = F0 + (1.0 - F0) / 21.0;
    vec3 Fms = FssEss * Favg / (1.0 - Ems * Favg);
    vec3 kD = albedo * (1.0 - metallic) * (1.0 - (FssEss + Fms * Ems));
    vec3 irradiance = textureLod(uIrradianceMap, N, 0.0).rgb;
    vec3 prefiltered = textureLod(uPrefilterMap, reflect(-V, N), roughness * uPrefilterMaxLod).rgb;
    return (FssEss * prefiltered + (Fms * Ems + kD) * irradiance) * ao;
    // END SOLUTION
}
