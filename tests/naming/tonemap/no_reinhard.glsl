// expect: no Reinhard denominator
// Only the gamma; the tone map forgotten (values above 1 stay above 1).
vec3 displayEncode(vec3 hdr)
{
    return pow(max(hdr, vec3(0.0)), vec3(1.0 / 2.2));
}
