// correct: clamp() on the mapped value and the exponent written as a constant
vec3 displayEncode(vec3 hdr)
{
    vec3 mapped = clamp(hdr / (vec3(1.0) + hdr), 0.0, 1.0);
    return pow(mapped, vec3(0.4545454545));
}
