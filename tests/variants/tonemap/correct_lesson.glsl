// correct: the lesson's two lines (no guard for negative input)
vec3 displayEncode(vec3 hdr)
{
    vec3 color = hdr / (hdr + vec3(1.0));
    color = pow(color, vec3(1.0 / 2.2));
    return color;
}
