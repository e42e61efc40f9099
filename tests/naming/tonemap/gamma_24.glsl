// expect: gamma 2.4 (exponent 1/2.4)
// sRGB's exponent 2.4 without its linear toe.
vec3 displayEncode(vec3 hdr)
{
    vec3 c = max(hdr, vec3(0.0));
    vec3 reinhard = c / (c + 1.0);
    return pow(reinhard, vec3(1.0 / 2.4));
}
