// correct: reflect() for L, clamp() for the cosine, an int loop counter
vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)
{
    vec3 color = vec3(0.0);
    float totalWeight = 0.0;
    for (int i = 0; i < int(sampleCount); ++i) {
        vec3 H = importanceSampleGGX(hammersley(uint(i), sampleCount), R, roughness);
        vec3 L = reflect(-R, H);
        float NdotL = clamp(dot(R, L), 0.0, 1.0);
        color += textureLod(uEnvironment, L, 0.0).rgb * NdotL;
        totalWeight += NdotL;
    }
    return color / max(totalWeight, 1e-4);
}
