// correct: the estimator written as f (N.L) / pdf with D in both (not cancelled by hand),
// clamp instead of max, other epsilons
float ggxNdf(float NdotH, float roughness)
{
    float a2 = max(pow(roughness, 4.0), 1e-7);
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

float schlickGgxIbl(float x, float roughness)
{
    float k = max(roughness * roughness, 1e-3) / 2.0;
    return x / (x * (1.0 - k) + k);
}

vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = clamp(dot(N, V), 1e-3, 1.0);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < sampleCount; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, sampleCount), N, roughness);
        vec3 L = normalize(2.0 * dot(V, H) * H - V);
        float NdotL = dot(N, L);
        if (NdotL <= 0.0) continue;
        float NdotH = clamp(dot(N, H), 1e-3, 1.0);
        float VdotH = clamp(dot(V, H), 1e-3, 1.0);
        float D = ggxNdf(NdotH, roughness);
        float G = schlickGgxIbl(NdotV, roughness) * schlickGgxIbl(NdotL, roughness);
        vec3 F = fresnelSchlick(VdotH, F0);
        vec3 f = D * G * F / (4.0 * NdotV * NdotL);
        float pdf = D * NdotH / (4.0 * VdotH);
        sum += textureLod(uEnvironment, L, 0.0).rgb * f * NdotL / pdf;
    }
    return sum / float(sampleCount);
}
