// expect: divided by 2^31 instead of 2^32
// mistake: the reversed bits divided by 2^31 instead of 2^32, so y covers [0, 2)
vec2 hammersley(uint i, uint n)
{
    return vec2(float(i) / float(n), float(bitfieldReverse(i)) / 2147483648.0);
}
