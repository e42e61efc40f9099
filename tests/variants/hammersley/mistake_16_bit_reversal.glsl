// mistake: the radical inverse of the low 16 bits of i only (right for every i < 65536, which
// is all the discrepancy view draws)
// expect: ignores the bits of i above bit 15
vec2 hammersley(uint i, uint n)
{
    uint b = i & 0xFFFFu;
    b = ((b & 0x00FFu) << 8u) | ((b & 0xFF00u) >> 8u);
    b = ((b & 0x0F0Fu) << 4u) | ((b & 0xF0F0u) >> 4u);
    b = ((b & 0x3333u) << 2u) | ((b & 0xCCCCu) >> 2u);
    b = ((b & 0x5555u) << 1u) | ((b & 0xAAAAu) >> 1u);
    return vec2(float(i) / float(n), float(b) / 65536.0);
}
