// expect: read along H instead of the reflected L
// mistake: the environment read along H instead of the reflected L = reflect(-R, H) (a lobe
// about half as wide)
vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)
{
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < sampleCount; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, sampleCount), R, roughness);
        float NdotH = dot(R, H);
        if (NdotH > 0.0) {
            sum += textureLod(uEnvironment, H, 0.0).rgb * NdotH;
            weight += NdotH;
        }
    }
    return sum / max(weight, 1e-4);
}
