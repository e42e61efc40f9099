// expect: fits the reference without PI
// mistake: Lambert diffuse without the 1/PI normalisation
vec3 cookTorranceBRDF(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 H = halfwayVector(L, V);
    vec3 F = fresnelSchlick(max(dot(H, V), 0.0), F0);
    vec3 kD = (vec3(1.0) - F) * (1.0 - metallic);
    return kD * albedo + cookTorranceSpecular(N, V, L, F0, roughness);
}
