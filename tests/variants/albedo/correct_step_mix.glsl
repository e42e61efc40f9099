// correct: exact sRGB curve, branches blended with step() instead of a boolean mix
vec3 srgbToLinear(vec3 c)
{
    vec3 x = clamp(c, 0.0, 1.0);
    vec3 linearPart = x * (1.0 / 12.92);
    vec3 powerPart = pow((x + vec3(0.055)) * (1.0 / 1.055), vec3(2.4));
    return mix(linearPart, powerPart, step(vec3(0.04045), x));
}
