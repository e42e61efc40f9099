// Hammersley point set: n points in the unit square whose x coordinates are evenly spaced
// (i / n) and whose y coordinates are the base-2 radical inverse of i (Van der Corput): the
// binary digits of i mirrored around the binary point, e.g. i = 6 = 110b -> 0.011b = 0.375.
// Every dyadic box of area 1/n then holds exactly one point (for n a power of two), so sums
// over these points converge faster than over random ones.
vec2 hammersley(uint i, uint n)
{
    // BEGIN SOLUTION
    // Mirroring the 32 bits of i is exactly bitfieldReverse; dividing by 2^32 puts the binary
    // point in front. The float is exact for i < 2^24 (at most 24 significant bits).
    float radicalInverse = float(bitfieldReverse(i)) * 2.3283064365386963e-10;
    // max(n, 1u): n = 0 would divide by zero.
    return vec2(float(i) / float(max(n, 1u)), radicalInverse);
    // END SOLUTION
}
