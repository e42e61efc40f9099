// correct: independent pseudo-random samples (an integer hash of the inputs and i) instead
// of Hammersley points, seeded by the inputs and SEED (tests/test_estimator_seeds.cpp grades
// it at 200 values); V in the yz plane
const uint SEED = 0u;

uint lutHash(uint x)
{
    x ^= x >> 17u;
    x *= 0xed5ad4bbu;
    x ^= x >> 11u;
    x *= 0xac4c1b51u;
    x ^= x >> 15u;
    x *= 0x31848babu;
    x ^= x >> 14u;
    return x;
}

vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)
{
    NdotV = clamp(NdotV, 1e-4, 1.0);
    vec3 V = vec3(0.0, sqrt(1.0 - NdotV * NdotV), NdotV);
    uint n = max(sampleCount, 1u);
    float k = max(roughness * roughness, 1e-3) * 0.5;
    uint seed = lutHash(floatBitsToUint(NdotV) ^ lutHash(floatBitsToUint(roughness) ^ lutHash(SEED)));
    vec2 sum = vec2(0.0);
    for (uint i = 0u; i < n; ++i) {
        uint h = lutHash(seed ^ (i * 0x9e3779b9u));
        vec2 xi = vec2(float(h & 0xffffu), float(h >> 16u)) / 65536.0;
        vec3 H = importanceSampleGGX(xi, vec3(0.0, 0.0, 1.0), roughness);
        vec3 L = reflect(-V, H);
        if (L.z <= 0.0) continue;
        float VdotH = clamp(dot(V, H), 0.0, 1.0);
        float G = NdotV / (NdotV * (1.0 - k) + k) * (L.z / (L.z * (1.0 - k) + k));
        float Gvis = G * VdotH / (max(H.z, 1e-4) * NdotV);
        float Fc = pow(1.0 - VdotH, 5.0);
        sum += vec2((1.0 - Fc) * Gvis, Fc * Gvis);
    }
    return sum / float(n);
}
