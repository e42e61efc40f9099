// mistake: n capped at 1024 (the largest count the discrepancy view draws)
// expect: ignores its count above 1024
vec2 hammersley(uint i, uint n)
{
    uint m = clamp(n, 1u, 1024u);
    return vec2(float(i) / float(m), float(bitfieldReverse(i)) * 2.3283064365386963e-10);
}
