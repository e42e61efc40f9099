// expect: 1/12.92 x the albedo texel at every point
// mistake: only the linear toe of the sRGB curve (c / 12.92) applied to the whole range
vec3 srgbToLinear(vec3 c)
{
    return c / 12.92;
}
