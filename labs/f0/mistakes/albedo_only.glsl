// expect: the albedo itself at every point
// mistake: F0 = albedo for every material, dielectrics included
vec3 baseReflectivity(vec3 albedo, float metallic)
{
    return albedo;
}
