// Reflectance at normal incidence (F0). Dielectrics reflect about 4% of light, uncoloured;
// metals reflect most of it, tinted, and that tint is what the albedo stores for them.
// The metallic parameter blends between the two.
vec3 baseReflectivity(vec3 albedo, float metallic)
{
    // BEGIN SOLUTION
    return mix(vec3(0.04), albedo, metallic);
    // END SOLUTION
}
