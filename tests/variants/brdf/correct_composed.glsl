// correct: composed from the contract functions, clamp instead of max, diffuse factored
vec3 cookTorranceBRDF(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 F = fresnelSchlick(clamp(dot(halfwayVector(L, V), V), 0.0, 1.0), F0);
    vec3 diffuse = (1.0 - metallic) * (vec3(1.0) - F) * (albedo * (1.0 / PI));
    return diffuse + cookTorranceSpecular(N, V, L, F0, roughness);
}
