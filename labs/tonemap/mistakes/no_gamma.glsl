// expect: fits no gamma (exponent 1) where the reference has gamma 2.2
// mistake: Reinhard only, the display encoding (gamma 1/2.2) is missing
vec3 displayEncode(vec3 hdr)
{
    vec3 c = max(hdr, vec3(0.0));
    return c / (c + 1.0);
}
