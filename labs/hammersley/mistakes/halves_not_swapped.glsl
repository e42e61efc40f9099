// expect: misses its first step (the 16-bit halves)
// mistake: the swap network misses its first step (the 16-bit halves), so the low bits of i
// end up reversed in the low half: y = reverse16(i) / 2^32, all below 2^-16
vec2 hammersley(uint i, uint n)
{
    uint b = i;
    b = ((b & 0x00FF00FFu) << 8u) | ((b & 0xFF00FF00u) >> 8u);
    b = ((b & 0x0F0F0F0Fu) << 4u) | ((b & 0xF0F0F0F0u) >> 4u);
    b = ((b & 0x33333333u) << 2u) | ((b & 0xCCCCCCCCu) >> 2u);
    b = ((b & 0x55555555u) << 1u) | ((b & 0xAAAAAAAAu) >> 1u);
    return vec2(float(i) / float(n), float(b) * 2.3283064365386963e-10);
}
