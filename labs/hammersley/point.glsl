// The point hammersley(i, n) itself, for the grader's checks over every bit of i and counts up
// to 2^20 (not a picture): i = extra.x * 65536 + extra.y (two 16-bit halves, each exact in a
// float), n = extra.z.
vec3 view(Surface s)
{
    uint i = (uint(s.extra.x) << 16u) | uint(s.extra.y);
    return vec3(hammersley(i, uint(s.extra.z)), 0.0);
}
