// expect: fits the reference without N.L: is the N.L weight of each sample missing
// mistake: a plain average of the samples above the horizon, without the N.L weights
vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)
{
    vec3 sum = vec3(0.0);
    float count = 0.0;
    for (uint i = 0u; i < sampleCount; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, sampleCount), R, roughness);
        vec3 L = 2.0 * dot(R, H) * H - R;
        if (dot(R, L) > 0.0) {
            sum += textureLod(uEnvironment, L, 0.0).rgb;
            count += 1.0;
        }
    }
    return sum / max(count, 1.0);
}
