// A correct variant: a jittered grid of sqrt(n) x sqrt(n) strata where n is a square, else
// Hammersley's points; the same weight written with G2 / G1 spelled out.
float ownSchlickGGX(float NdotX, float roughness)
{
    float x = max(NdotX, 0.0);
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    return x / (x * (1.0 - k) + k);
}

vec3 specularIBLVisible(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = max(dot(N, V), 1e-4);
    float a2 = max(roughness * roughness, 3.1622777e-4);
    a2 *= a2;
    float smithG1 = 2.0 * NdotV / (NdotV + sqrt(a2 + (1.0 - a2) * NdotV * NdotV));
    uint n = max(sampleCount, 1u);
    uint side = uint(floor(sqrt(float(n)) + 0.5));
    bool grid = side * side == n;
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec2 u = grid ? (vec2(float(i % side), float(i / side)) +
                         fract(vec2(0.7548776662, 0.5698402910) * float(i + 1u))) / float(side)
                      : hammersley(i, n);
        vec3 H = importanceSampleVNDF(u, N, V, roughness);
        vec3 L = reflect(-V, H);
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            float G2 = ownSchlickGGX(NdotV, roughness) * ownSchlickGGX(NdotL, roughness);
            sum += textureLod(uEnvironment, L, 0.0).rgb *
                   fresnelSchlick(max(dot(V, H), 0.0), F0) * G2 / smithG1;
        }
    }
    return sum / float(n);
}
