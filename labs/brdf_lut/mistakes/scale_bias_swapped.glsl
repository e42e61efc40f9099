// expect: Your components are swapped
// mistake: returns (B, A): the Fresnel-weighted part in the red channel
vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)
{
    NdotV = clamp(NdotV, 1e-4, 1.0);
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 V = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    float k = roughness * roughness / 2.0;
    float A = 0.0, B = 0.0;
    for (uint i = 0u; i < sampleCount; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, sampleCount), N, roughness);
        vec3 L = reflect(-V, H);
        if (L.z > 0.0) {
            float VdotH = clamp(dot(V, H), 0.0, 1.0);
            float G = (NdotV / (NdotV * (1.0 - k) + k)) * (L.z / (L.z * (1.0 - k) + k));
            float gVis = G * VdotH / (max(H.z, 1e-4) * NdotV);
            float fc = pow(1.0 - VdotH, 5.0);
            A += (1.0 - fc) * gVis;
            B += fc * gVis;
        }
    }
    return vec2(B, A) / float(sampleCount);
}
