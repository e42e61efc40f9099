// expect: the diffuse weight kD missing
// The diffuse part not weighted by kD.
vec3 ambientIBL(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    float NdotV = max(dot(N, V), 0.0);
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 irradiance = textureLod(uIrradianceMap, N, 0.0).rgb;
    vec3 prefiltered = textureLod(uPrefilterMap, reflect(-V, N), roughness * uPrefilterMaxLod).rgb;
    vec2 AB = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).rg;
    return (albedo * irradiance + prefiltered * (F0 * AB.x + AB.y)) * ao;
}
