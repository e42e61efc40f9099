// expect: fits the exponent 2.2
// mistake: gamma 2.2 instead of 1/2.2 (decodes instead of encoding for the display)
vec3 displayEncode(vec3 hdr)
{
    vec3 c = max(hdr, vec3(0.0));
    c = c / (c + 1.0);
    return pow(c, vec3(2.2));
}
