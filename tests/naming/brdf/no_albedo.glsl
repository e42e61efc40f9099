// expect: the albedo in the diffuse term missing
// The diffuse term forgets the albedo.
vec3 cookTorranceBRDF(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 F = fresnelSchlick(max(dot(halfwayVector(L, V), V), 0.0), F0);
    vec3 diffuse = (1.0 - F) * (1.0 - metallic) / PI;
    return diffuse + cookTorranceSpecular(N, V, L, F0, roughness);
}
