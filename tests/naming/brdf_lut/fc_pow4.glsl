// expect: Fc = (1 - V.H)^4 where
// The Schlick factor with a fourth power.
vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)
{
    NdotV = clamp(NdotV, 1e-4, 1.0);
    vec3 V = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    uint n = max(sampleCount, 1u);
    vec2 sum = vec2(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), vec3(0.0, 0.0, 1.0), roughness);
        float VdotH = dot(V, H);
        vec3 L = 2.0 * VdotH * H - V;
        if (L.z > 0.0) {
            VdotH = clamp(VdotH, 0.0, 1.0);
            float G = NdotV / (NdotV * (1.0 - k) + k) * L.z / (L.z * (1.0 - k) + k);
            float w = G * VdotH / (max(H.z, 1e-4) * NdotV);
            float m = 1.0 - VdotH;
            float Fc = (m * m) * (m * m);
            sum += vec2((1.0 - Fc) * w, Fc * w);
        }
    }
    return sum / float(n);
}
