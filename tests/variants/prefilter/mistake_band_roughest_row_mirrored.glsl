// mistake: a shortcut meant for the mirror (roughness 0) written for the other end: at
// roughness 1 the environment is read along R alone, unblurred.
// Fails by the value band alone (test_variants.cpp, mistake_band_*): only the probe's top row
// (roughness exactly 1, which random inputs in [0, 1) never reach) is wrong, 6% of the probe.
// expect: wrong only where roughness >
vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)
{
    if (roughness >= 1.0) return textureLod(uEnvironment, R, 0.0).rgb;
    vec3 N = R;
    vec3 V = R;
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            sum += textureLod(uEnvironment, L, 0.0).rgb * NdotL;
            weight += NdotL;
        }
    }
    // weight >= 1 as soon as sample 0 (H = N, N.L = 1) is used; the fallback keeps 0/0 out.
    return weight > 0.0 ? sum / weight : textureLod(uEnvironment, R, 0.0).rgb;
}
