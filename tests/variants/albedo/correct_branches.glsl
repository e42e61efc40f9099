// correct: exact sRGB curve written per channel with if/else
float channelToLinear(float v)
{
    if (v <= 0.04045) {
        return v / 12.92;
    }
    return pow((v + 0.055) / 1.055, 2.4);
}

vec3 srgbToLinear(vec3 c)
{
    return vec3(channelToLinear(c.r), channelToLinear(c.g), channelToLinear(c.b));
}
