// expect: the albedo texel itself at every point
// mistake: no linearisation, the sRGB-encoded value is used as linear reflectance
vec3 srgbToLinear(vec3 c)
{
    return c;
}
