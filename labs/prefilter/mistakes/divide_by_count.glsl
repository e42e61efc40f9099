// expect: divided by the sample count instead of the sum of weights
// mistake: the N.L-weighted sum divided by the sample count instead of the sum of weights
// (the result is darkened by the mean N.L)
vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)
{
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < sampleCount; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, sampleCount), R, roughness);
        vec3 L = 2.0 * dot(R, H) * H - R;
        float NdotL = dot(R, L);
        if (NdotL > 0.0) sum += textureLod(uEnvironment, L, 0.0).rgb * NdotL;
    }
    return sum / float(sampleCount);
}
