// expect: fits the reference with the gamma applied before Reinhard
// mistake: gamma applied before tone mapping (order of the two steps swapped)
vec3 displayEncode(vec3 hdr)
{
    vec3 c = pow(max(hdr, vec3(0.0)), vec3(1.0 / 2.2));
    return c / (c + 1.0);
}
