// correct: Hammersley points under a Cranley-Patterson rotation (one random offset modulo 1
// from SEED, the same at every pixel) with filtered importance sampling (each sample reads the
// mip whose texel covers the solid angle 1 / (n pdf) it stands for), the frame from the x axis.
// tests/test_estimator_seeds.cpp grades it at 200 values of SEED.
const uint SEED = 0u;

uint rotationHash(uint x)
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
    vec3 axis = abs(N.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 0.0, 1.0);
    vec3 T = normalize(cross(N, axis));
    vec3 B = cross(T, N);
    vec2 shift = vec2(float(rotationHash(2u * SEED + 1u) >> 8u),
                      float(rotationHash(2u * SEED + 2u) >> 8u)) / 16777216.0;
    float size = float(textureSize(uEnvironment, 0).x);
    float texelSolidAngle = 4.0 * PI / (6.0 * size * size);
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < n; ++i) {
        vec2 xi = fract(vec2(float(i) / float(n), float(bitfieldReverse(i)) * 2.3283064e-10) +
                        shift);
        float phi = 2.0 * PI * xi.x;
        float cosTheta = sqrt((1.0 - xi.y) / (1.0 + (a2 - 1.0) * xi.y));
        float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
        vec3 H = T * (sinTheta * cos(phi)) + B * (sinTheta * sin(phi)) + N * cosTheta;
        vec3 L = 2.0 * dot(R, H) * H - R;
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            // pdf of L with V = N: D (N.H) / (4 V.H) = D / 4
            float d = cosTheta * cosTheta * (a2 - 1.0) + 1.0;
            float pdf = max(a2 / (PI * d * d) * 0.25, 1e-8);
            float lod = roughness == 0.0
                            ? 0.0
                            : max(0.5 * log2(1.0 / (float(n) * pdf * texelSolidAngle)) + 1.0, 0.0);
            sum += textureLod(uEnvironment, L, lod).rgb * NdotL;
            weight += NdotL;
        }
    }
    return weight > 0.0 ? sum / weight : textureLod(uEnvironment, R, 0.0).rgb;
}
