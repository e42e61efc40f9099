// The second factor of the split sum: with Schlick's Fresnel F = F0 + (1 - F0) Fc,
// Fc = (1 - V.H)^5, the specular reflectance under white light is F0 * A + B with
//     A = E[(1 - Fc) G_vis],   B = E[Fc G_vis],   G_vis = G (V.H) / ((N.H)(N.V)),
// over GGX importance samples. A and B depend only on N.V and roughness: a 2D table. N = +z
// and V is placed in the xz plane at the given N.V. IBL uses k = roughness^2 / 2 in G.

// Schlick-GGX with k = alpha / 2, alpha floored like D (keeps k > 0 and A + B <= 1 at
// roughness 0 and N.V -> 0).
float pbrlab_lutGeometrySchlickGGX(float NdotX, float roughness)
{
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    return NdotX / (NdotX * (1.0 - k) + k);
}

vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)
{
    // BEGIN SOLUTION
    // N.V clamped to [1e-4, 1]: it divides G_vis, and V needs sqrt(1 - N.V^2).
    NdotV = clamp(NdotV, 1e-4, 1.0);
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
    // END SOLUTION
}
