// Colour textures store sRGB-encoded values, spaced for the eye rather than for energy.
// Light adds and scales linearly, so the albedo must be decoded to linear reflectance
// (the exact IEC 61966-2-1 curve: a linear toe, then a 2.4 power) before any shading.
vec3 srgbToLinear(vec3 c)
{
    // BEGIN SOLUTION
    c = clamp(c, 0.0, 1.0);
    vec3 low = c / 12.92;
    vec3 high = pow((c + 0.055) / 1.055, vec3(2.4));
    return mix(high, low, lessThanEqual(c, vec3(0.04045)));
    // END SOLUTION
}
