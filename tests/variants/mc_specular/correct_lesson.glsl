// correct: the seed's SpecularIBL loop with the IBL k, reflect() for L, no guards of its own
vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = max(dot(N, V), 0.0);
    float k = roughness * roughness / 2.0;
    vec3 color = vec3(0.0);
    for (uint i = 0u; i < sampleCount; i++) {
        vec2 Xi = hammersley(i, sampleCount);
        vec3 H = importanceSampleGGX(Xi, N, roughness);
        vec3 L = reflect(-V, H);
        float NdotL = max(dot(N, L), 0.0);
        float NdotH = max(dot(N, H), 0.0);
        float VdotH = max(dot(V, H), 0.0);
        if (NdotL > 0.0) {
            float G = (NdotV / (NdotV * (1.0 - k) + k)) * (NdotL / (NdotL * (1.0 - k) + k));
            vec3 F = fresnelSchlick(VdotH, F0);
            color += textureLod(uEnvironment, L, 0.0).rgb * F * G * VdotH / (NdotH * NdotV);
        }
    }
    return color / float(sampleCount);
}
