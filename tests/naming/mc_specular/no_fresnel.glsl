// expect: the Fresnel term F missing
// The Fresnel term left out of each sample.
vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = max(dot(N, V), 1e-4);
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        float VdotH = dot(V, H);
        vec3 L = 2.0 * VdotH * H - V;
        float NdotL = dot(N, L);
        if (NdotL <= 0.0) continue;
        float G = NdotV / (NdotV * (1.0 - k) + k) * NdotL / (NdotL * (1.0 - k) + k);
        sum += textureLod(uEnvironment, L, 0.0).rgb * G * max(VdotH, 0.0) /
               (max(dot(N, H), 1e-4) * NdotV);
    }
    return sum / float(n);
}
