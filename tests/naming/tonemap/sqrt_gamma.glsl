// expect: gamma 2 (exponent 1/2)
// The display gamma approximated by a square root.
vec3 displayEncode(vec3 hdr)
{
    vec3 mapped = max(hdr, 0.0) / (max(hdr, 0.0) + vec3(1.0));
    return sqrt(mapped);
}
