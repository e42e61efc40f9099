// correct: Reinhard written as 1 - 1/(1 + x)
vec3 displayEncode(vec3 hdr)
{
    vec3 x = max(hdr, vec3(0.0));
    return pow(vec3(1.0) - vec3(1.0) / (vec3(1.0) + x), vec3(1.0 / 2.2));
}
