// correct: the common gamma-2.2 approximation of the sRGB curve (lesson style)
vec3 srgbToLinear(vec3 c)
{
    return pow(c, vec3(2.2));
}
