// correct: another low-discrepancy set, the golden-ratio (Fibonacci lattice) points
// (i + 0.5) / n and fract(i phi), through the contract's importanceSampleGGX
vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = max(dot(N, V), 1e-4);
    float k = max(roughness * roughness, 1e-3) / 2.0;
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec2 xi = vec2(fract(float(i) * 0.6180339887), (float(i) + 0.5) / float(n));
        vec3 H = importanceSampleGGX(xi, N, roughness);
        vec3 L = reflect(-V, H);
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            float VdotH = max(dot(V, H), 0.0);
            float G = NdotV / (NdotV * (1.0 - k) + k) * (NdotL / (NdotL * (1.0 - k) + k));
            sum += textureLod(uEnvironment, L, 0.0).rgb * fresnelSchlick(VdotH, F0) * G *
                   VdotH / (max(dot(N, H), 1e-4) * NdotV);
        }
    }
    return sum / float(n);
}
