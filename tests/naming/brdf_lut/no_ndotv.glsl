// expect: N.V in G_vis = G V.H / (N.H N.V) missing
// G_vis without its division by N.V.
vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)
{
    float nv = clamp(NdotV, 1e-4, 1.0);
    vec3 V = vec3(sqrt(1.0 - nv * nv), 0.0, nv);
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    float A = 0.0, B = 0.0;
    uint n = max(sampleCount, 1u);
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), vec3(0.0, 0.0, 1.0), roughness);
        float vh = dot(V, H);
        vec3 L = 2.0 * vh * H - V;
        if (L.z <= 0.0) continue;
        vh = clamp(vh, 0.0, 1.0);
        float G = (nv / (nv * (1.0 - k) + k)) * (L.z / (L.z * (1.0 - k) + k));
        float Gvis = G * vh / max(H.z, 1e-4);
        float Fc = pow(1.0 - vh, 5.0);
        A += (1.0 - Fc) * Gvis;
        B += Fc * Gvis;
    }
    return vec2(A, B) / float(n);
}
