// expect: clamp(hdr, 0, 1)^(1/2.2) at every point
// mistake: HDR clipped to [0, 1] instead of tone mapped
vec3 displayEncode(vec3 hdr)
{
    return pow(clamp(hdr, 0.0, 1.0), vec3(1.0 / 2.2));
}
