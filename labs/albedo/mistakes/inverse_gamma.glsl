// expect: the albedo texel^(1/2.2) at every point
// mistake: gamma applied the wrong way round (encodes with 1/2.2 instead of decoding)
vec3 srgbToLinear(vec3 c)
{
    return pow(c, vec3(1.0 / 2.2));
}
