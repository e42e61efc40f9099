// correct: V placed in the yz plane instead of xz, reflect() for L, clamp(N.V, 1e-3, 1)
float lutG1(float x, float roughness)
{
    float k = roughness * roughness * 0.5;
    return x / (x * (1.0 - k) + k + 1e-7);
}

vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)
{
    NdotV = clamp(NdotV, 1e-3, 1.0);
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 V = vec3(0.0, sqrt(1.0 - NdotV * NdotV), NdotV);
    vec2 ab = vec2(0.0);
    for (uint i = 0u; i < sampleCount; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, sampleCount), N, roughness);
        vec3 L = reflect(-V, H);
        float NdotL = clamp(L.z, 0.0, 1.0);
        if (NdotL > 0.0) {
            float VdotH = clamp(dot(V, H), 0.0, 1.0);
            float NdotH = clamp(H.z, 1e-3, 1.0);
            float G = lutG1(NdotV, roughness) * lutG1(NdotL, roughness);
            float gVis = G * VdotH / (NdotH * NdotV);
            float fc = pow(1.0 - VdotH, 5.0);
            ab += vec2(1.0 - fc, fc) * gVis;
        }
    }
    return ab / float(sampleCount);
}
