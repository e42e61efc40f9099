// correct: filtered importance sampling (Krivanek and Colbert, GPU Gems 3 ch. 20), as
// pbrlab's own precompute does: each sample reads the environment mip whose texel covers the
// solid angle 1 / (n pdf) it stands for
vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)
{
    vec3 N = R, V = R;
    uint n = max(sampleCount, 1u);
    float sourceSize = float(textureSize(uEnvironment, 0).x);
    float texelSolidAngle = 4.0 * PI / (6.0 * sourceSize * sourceSize);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            float pdf = max(distributionGGX(N, H, roughness) * 0.25, 1e-8);
            float sampleSolidAngle = 1.0 / (float(n) * pdf);
            float lod = roughness == 0.0 ? 0.0
                        : max(0.5 * log2(sampleSolidAngle / texelSolidAngle) + 1.0, 0.0);
            sum += textureLod(uEnvironment, L, lod).rgb * NdotL;
            weight += NdotL;
        }
    }
    return weight > 0.0 ? sum / weight : textureLod(uEnvironment, R, 0.0).rgb;
}
