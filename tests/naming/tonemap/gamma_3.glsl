// expect: gamma 3 (exponent 1/3)
// Gamma 3 instead of 2.2.
vec3 displayEncode(vec3 hdr)
{
    vec3 x = max(hdr, vec3(0.0));
    x = x / (1.0 + x);
    return pow(x, vec3(1.0 / 3.0));
}
