// expect: Fc = (1 - N.V)^5, where
// The Schlick factor taken at N.V once for all samples.
vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)
{
    NdotV = clamp(NdotV, 1e-4, 1.0);
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 V = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    float k = max(roughness * roughness, 3.1622777e-4) / 2.0;
    float Fc = pow(1.0 - NdotV, 5.0);
    uint n = max(sampleCount, 1u);
    vec2 ab = vec2(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        vec3 L = 2.0 * dot(V, H) * H - V;
        if (L.z > 0.0) {
            float VdotH = clamp(dot(V, H), 0.0, 1.0);
            float G = NdotV / (NdotV * (1.0 - k) + k) * L.z / (L.z * (1.0 - k) + k);
            float Gvis = G * VdotH / (max(H.z, 1e-4) * NdotV);
            ab += vec2(1.0 - Fc, Fc) * Gvis;
        }
    }
    return ab / float(n);
}
