// expect: fits the reference without (1 - metallic)
// mistake: kD = 1 - F without the (1 - metallic) factor (metals keep a diffuse term)
vec3 cookTorranceBRDF(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 H = halfwayVector(L, V);
    vec3 F = fresnelSchlick(max(dot(H, V), 0.0), F0);
    vec3 kD = vec3(1.0) - F;
    return kD * albedo / PI + cookTorranceSpecular(N, V, L, F0, roughness);
}
