// expect: the reference + 0.04 x metallic everywhere
// mistake: the metal tint is added to 0.04 instead of interpolated
vec3 baseReflectivity(vec3 albedo, float metallic)
{
    return vec3(0.04) + albedo * metallic;
}
