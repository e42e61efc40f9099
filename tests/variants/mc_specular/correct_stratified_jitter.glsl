// correct: stratified jittered samples (the i-th of n strata of the polar coordinate, jittered
// inside it, the azimuth at random; xorshift random numbers seeded by N, V and SEED), a frame
// from the world's up axis, the pdf written out: f (N.L) / pdf with pdf = D (N.H) / (4 V.H).
// tests/test_estimator_seeds.cpp grades it at 200 values of SEED.
const uint SEED = 0u;

uint jitterHash(uint x)
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

vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = max(dot(N, V), 1e-4);
    float a = roughness * roughness;
    float a2 = max(a * a, 1e-7);
    float k = max(a, 3.1622777e-4) * 0.5;
    vec3 up = abs(N.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 T = normalize(cross(up, N));
    vec3 B = cross(N, T);
    uint state = jitterHash(floatBitsToUint(N.x + 3.0 * V.y) ^
                            jitterHash(floatBitsToUint(N.z - V.x) ^
                                       jitterHash(floatBitsToUint(N.y + V.z) + SEED)));
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        state ^= state << 13u;
        state ^= state >> 17u;
        state ^= state << 5u;
        float jitter = float(state >> 8u) / 16777216.0;
        state ^= state << 13u;
        state ^= state >> 17u;
        state ^= state << 5u;
        float azimuth = float(state >> 8u) / 16777216.0;
        float u = (float(i) + jitter) / float(n);
        float cosTheta = sqrt((1.0 - u) / (1.0 + (a2 - 1.0) * u));
        float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
        float phi = 2.0 * PI * azimuth;
        vec3 H = T * (sinTheta * cos(phi)) + B * (sinTheta * sin(phi)) + N * cosTheta;
        vec3 L = reflect(-V, H);
        float NdotL = dot(N, L);
        float VdotH = dot(V, H);
        if (NdotL <= 0.0 || VdotH <= 0.0) continue;
        float NdotH = max(dot(N, H), 1e-4);
        float D = a2 / (PI * pow(NdotH * NdotH * (a2 - 1.0) + 1.0, 2.0));
        float pdf = D * NdotH / (4.0 * VdotH);
        float G = NdotV / (NdotV * (1.0 - k) + k) * (NdotL / (NdotL * (1.0 - k) + k));
        vec3 f = D * G * fresnelSchlick(VdotH, F0) / (4.0 * NdotV * NdotL);
        sum += textureLod(uEnvironment, L, 0.0).rgb * f * NdotL / pdf;
    }
    return sum / float(n);
}
