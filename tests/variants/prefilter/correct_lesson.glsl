// correct: the seed's PrefilterEnvMap (N = V = R, N.L weights, no guard of its own)
vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)
{
    vec3 N = R;
    vec3 V = R;
    vec3 prefilteredColor = vec3(0.0);
    float totalWeight = 0.0;
    for (uint i = 0u; i < sampleCount; i++) {
        vec2 Xi = hammersley(i, sampleCount);
        vec3 H = importanceSampleGGX(Xi, N, roughness);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NdotL = clamp(dot(N, L), 0.0, 1.0);
        if (NdotL > 0.0) {
            prefilteredColor += NdotL * textureLod(uEnvironment, L, 0.0).rgb;
            totalWeight += NdotL;
        }
    }
    return prefilteredColor / totalWeight;
}
