// expect: comes from pow with a negative base (or 0 to a power <= 0), at line 31 of brdf_lut.glsl
// mistake: LearnOpenGL's LUT loop, V.H floored at 0 but not capped at 1: where V.H rounds to
// 1 + 1 ulp (V = H, roughness near 1, many samples) pow(1.0 - VdotH, 5.0) has a negative base
float GGX(float NdotV, float k)
{
    return NdotV / (NdotV * (1.0 - k) + k);
}

float G_Smith(float roughness, float NdotV, float NdotL)
{
    float k = (roughness) * (roughness) / 2.0;
    return GGX(NdotL, k) * GGX(NdotV, k);
}

vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)
{
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 V = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    float A = 0.0;
    float B = 0.0;
    for (uint i = 0u; i < sampleCount; i++) {
        vec2 Xi = hammersley(i, sampleCount);
        vec3 H = importanceSampleGGX(Xi, N, roughness);
        vec3 L = normalize(2.0 * dot(V, H) * H - V);
        float NdotL = max(L.z, 0.0);
        float NdotH = max(H.z, 0.0);
        float VdotH = max(dot(V, H), 0.0);
        if (NdotL > 0.0) {
            float G = G_Smith(roughness, NdotV, NdotL);
            float G_Vis = (G * VdotH) / (NdotH * NdotV);
            float Fc = pow(1.0 - VdotH, 5.0);
            A += (1.0 - Fc) * G_Vis;
            B += Fc * G_Vis;
        }
    }
    return vec2(A, B) / float(sampleCount);
}
