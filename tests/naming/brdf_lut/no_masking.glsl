// expect: the masking term G1(N.V) missing
// G with the light's G1 only.
vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)
{
    NdotV = clamp(NdotV, 1e-4, 1.0);
    vec3 V = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    uint n = max(sampleCount, 1u);
    float A = 0.0;
    float B = 0.0;
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), vec3(0.0, 0.0, 1.0), roughness);
        float VdotH = dot(V, H);
        vec3 L = 2.0 * VdotH * H - V;
        if (L.z > 0.0) {
            VdotH = clamp(VdotH, 0.0, 1.0);
            float G = L.z / (L.z * (1.0 - k) + k);
            float Gvis = G * VdotH / (max(H.z, 1e-4) * NdotV);
            float Fc = pow(1.0 - VdotH, 5.0);
            A += (1.0 - Fc) * Gvis;
            B += Fc * Gvis;
        }
    }
    return vec2(A, B) / float(n);
}
