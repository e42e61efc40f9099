// expect: returns 0.04 whatever the inputs
// mistake: F0 = 0.04 for every material, metals included
vec3 baseReflectivity(vec3 albedo, float metallic)
{
    return vec3(0.04);
}
