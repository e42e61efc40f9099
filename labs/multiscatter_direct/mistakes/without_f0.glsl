// expect: F0 in the compensation
// mistake: the lobe scaled by 1 / E for every material: only a white metal (F0 = 1) keeps all the light its bounces carry
vec3 cookTorranceBRDFMultiscatter(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 F = fresnelSchlick(max(dot(halfwayVector(L, V), V), 0.0), F0);
    vec3 kD = (1.0 - F) * (1.0 - metallic);
    vec2 AB = textureLod(uBrdfLut, vec2(max(dot(N, V), 0.0), roughness), 0.0).rg;
    float E = AB.x + AB.y;
    return kD * albedo / PI + cookTorranceSpecular(N, V, L, F0, roughness) / E;
}
