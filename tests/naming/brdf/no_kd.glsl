// expect: the diffuse weight kD missing
// The diffuse term not weighted by kD.
vec3 cookTorranceBRDF(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 specular = cookTorranceSpecular(N, V, L, baseReflectivity(albedo, metallic), roughness);
    vec3 lambert = albedo / PI;
    return lambert + specular;
}
