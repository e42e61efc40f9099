// correct: the estimator written as f (N.L) / pdf with the pdf formed from the contract's
// distributionGGX (pdf(L) = D (N.H) / (4 V.H)) and the whole Cook-Torrance lobe evaluated,
// D included: the D cancels only in the algebra
float mcG1(float NdotX, float roughness)
{
    float k = max(roughness * roughness, 1e-3) * 0.5;
    return NdotX / (NdotX * (1.0 - k) + k);
}

vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = max(dot(N, V), 1e-4);
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        vec3 L = reflect(-V, H);
        float NdotL = dot(N, L);
        if (NdotL <= 0.0) continue;
        float NdotH = max(dot(N, H), 1e-4);
        float VdotH = max(dot(V, H), 1e-4);
        float D = distributionGGX(N, H, roughness);
        float pdf = D * NdotH / (4.0 * VdotH);
        vec3 F = fresnelSchlick(VdotH, F0);
        float G = mcG1(NdotV, roughness) * mcG1(NdotL, roughness);
        vec3 f = D * G * F / (4.0 * NdotV * NdotL);
        sum += textureLod(uEnvironment, L, 0.0).rgb * f * NdotL / max(pdf, 1e-12);
    }
    return sum / float(n);
}
