// expect: the geometry term G missing
// The Monte Carlo weight without G.
vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = max(dot(N, V), 1e-4);
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        float VdotH = dot(V, H);
        vec3 L = 2.0 * VdotH * H - V;
        if (dot(N, L) > 0.0) {
            VdotH = max(VdotH, 0.0);
            float weight = VdotH / (max(dot(N, H), 1e-4) * NdotV);
            sum += textureLod(uEnvironment, L, 0.0).rgb * fresnelSchlick(VdotH, F0) * weight;
        }
    }
    return sum / float(n);
}
