// correct: radical inverse by a loop over the bits of i (weights 1/2, 1/4, ...), no bitfieldReverse
vec2 hammersley(uint i, uint n)
{
    float radicalInverse = 0.0;
    float weight = 0.5;
    for (uint bits = i; bits != 0u; bits >>= 1u) {
        if ((bits & 1u) != 0u) radicalInverse += weight;
        weight *= 0.5;
    }
    return vec2(float(i) / float(n), radicalInverse);
}
