// correct: linear interpolation written out by hand
vec3 baseReflectivity(vec3 albedo, float metallic)
{
    return vec3(0.04) * (1.0 - metallic) + albedo * metallic;
}
