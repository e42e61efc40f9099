// correct: stratified jittered samples (the i-th of n strata of the polar coordinate, jittered
// inside it, the azimuth at random; a hash of the inputs, i and SEED), GGX sampling of its own
// about N = +z, the weight with the IBL k. tests/test_estimator_seeds.cpp grades it at 200
// values of SEED.
const uint SEED = 0u;

uint strataHash(uint x)
{
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)
{
    NdotV = clamp(NdotV, 1e-4, 1.0);
    vec3 V = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    float a = roughness * roughness;
    float a2 = max(a * a, 1e-7);
    float k = max(a, 3.1622777e-4) * 0.5;
    uint seed = strataHash(floatBitsToUint(NdotV) ^ strataHash(floatBitsToUint(roughness) + SEED));
    uint n = max(sampleCount, 1u);
    vec2 sum = vec2(0.0);
    for (uint i = 0u; i < n; ++i) {
        uint h1 = strataHash(seed ^ (2u * i + 1u) * 0x9e3779b9u);
        uint h2 = strataHash(h1 ^ 0x85ebca6bu);
        float u = (float(i) + float(h1 >> 8u) / 16777216.0) / float(n);
        float phi = 2.0 * PI * float(h2 >> 8u) / 16777216.0;
        float cosTheta = sqrt((1.0 - u) / (1.0 + (a2 - 1.0) * u));
        float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
        vec3 H = vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
        float VdotH = dot(V, H);
        vec3 L = 2.0 * VdotH * H - V;
        if (L.z <= 0.0) continue;
        VdotH = clamp(VdotH, 0.0, 1.0);
        float G = NdotV / (NdotV * (1.0 - k) + k) * (L.z / (L.z * (1.0 - k) + k));
        float Gvis = G * VdotH / (max(H.z, 1e-4) * NdotV);
        float Fc = pow(1.0 - VdotH, 5.0);
        sum += vec2((1.0 - Fc) * Gvis, Fc * Gvis);
    }
    return sum / float(n);
}
