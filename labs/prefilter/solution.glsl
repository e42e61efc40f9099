// The first factor of the split sum: the environment blurred by the GGX lobe of a given
// roughness, stored per reflection direction R. The view is unknown when it is precomputed,
// so N = V = R is assumed, and the samples are weighted by N.L (Karis 2013), which matches
// the lobe's shape better than a plain average.
vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)
{
    // BEGIN SOLUTION
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
    // END SOLUTION
}
