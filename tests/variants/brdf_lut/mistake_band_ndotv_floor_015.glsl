// mistake: N.V clamped to [0.15, 1] instead of [1e-4, 1] (a floor to keep 1 / N.V small, set
// too high): the LUT's grazing columns hold the values at N.V = 0.15.
// Fails by the value band alone (test_variants.cpp, mistake_band_*): 15% of the LUT is wrong,
// the error keeps its sign there but 85% of each quarter of roughness is right, so the bias test's
// sum over a quarter stays within its limit.
// expect: outside the band
float pbrlab_lutGeometrySchlickGGX(float NdotX, float roughness)
{
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    return NdotX / (NdotX * (1.0 - k) + k);
}

vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)
{
    // N.V clamped (it divides G_vis, and V needs sqrt(1 - N.V^2)), the floor too high.
    NdotV = clamp(NdotV, 0.15, 1.0);
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 V = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    uint n = max(sampleCount, 1u);
    float A = 0.0;
    float B = 0.0;
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        float VdotH = dot(V, H);
        vec3 L = 2.0 * VdotH * H - V;
        float NdotL = L.z;
        if (NdotL > 0.0) {
            float NdotH = max(H.z, 1e-4);
            VdotH = clamp(VdotH, 0.0, 1.0);  // 1 - V.H must not go negative in pow
            float G = pbrlab_lutGeometrySchlickGGX(NdotV, roughness) *
                      pbrlab_lutGeometrySchlickGGX(NdotL, roughness);
            float Gvis = G * VdotH / (NdotH * NdotV);
            float Fc = pow(1.0 - VdotH, 5.0);
            A += (1.0 - Fc) * Gvis;
            B += Fc * Gvis;
        }
    }
    return vec2(A, B) / float(n);
}
