// A correct variant: another sequence, a hash of the sample's index and the pixel's inputs
// (plain Monte Carlo instead of Hammersley's points), with the solution's weight.
float ownSchlickGGX(float NdotX, float roughness)
{
    float x = max(NdotX, 0.0);
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    return x / (x * (1.0 - k) + k);
}

uint ownHash(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

vec3 specularIBLVisible(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = max(dot(N, V), 1e-4);
    float alpha = max(roughness * roughness, 3.1622777e-4);
    float tan2 = max(1.0 - NdotV * NdotV, 0.0) / (NdotV * NdotV);
    float G1v = 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2));
    uint seed = floatBitsToUint(N.x * 7.0 + V.y * 13.0 + roughness * 17.0);
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        uint h1 = ownHash(seed ^ (2u * i));
        uint h2 = ownHash(seed ^ (2u * i + 1u) ^ 0x9e3779b9u);
        vec2 u = vec2(float(h1 >> 8), float(h2 >> 8)) / 16777216.0;
        vec3 H = importanceSampleVNDF(u, N, V, roughness);
        float VdotH = max(dot(V, H), 0.0);
        vec3 L = 2.0 * VdotH * H - V;
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            float G = ownSchlickGGX(NdotV, roughness) * ownSchlickGGX(NdotL, roughness);
            sum += textureLod(uEnvironment, L, 0.0).rgb * fresnelSchlick(VdotH, F0) * (G / G1v);
        }
    }
    return sum / float(n);
}
