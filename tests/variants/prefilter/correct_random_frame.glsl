// correct: independent pseudo-random samples (a hash seeded by R) mapped to GGX half vectors
// in another frame, the Karis N.L weights
uint hashU(uint x)
{
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)
{
    vec3 N = R;
    float a = roughness * roughness;
    float a2 = max(a * a, 1e-7);
    vec3 axis = abs(N.x) < 0.6 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    vec3 T = normalize(axis - N * dot(N, axis));
    vec3 B = cross(N, T);
    uint seed = hashU(floatBitsToUint(R.x) ^ hashU(floatBitsToUint(R.y) ^ hashU(floatBitsToUint(R.z))));
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < n; ++i) {
        seed = hashU(seed + i);
        float u1 = float(seed & 0xffffu) / 65536.0;
        float u2 = float(seed >> 16u) / 65536.0;
        float phi = 2.0 * PI * u1;
        float cosTheta = sqrt((1.0 - u2) / ((1.0 - u2) + a2 * u2));
        float sinTheta = sqrt(a2 * u2 / ((1.0 - u2) + a2 * u2));
        vec3 H = T * (sinTheta * cos(phi)) + B * (sinTheta * sin(phi)) + N * cosTheta;
        vec3 L = reflect(-N, H);
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            sum += textureLod(uEnvironment, L, 0.0).rgb * NdotL;
            weight += NdotL;
        }
    }
    return weight > 0.0 ? sum / weight : textureLod(uEnvironment, R, 0.0).rgb;
}
