// expect: mc_specular's weight
// mistake: mc_specular's weight G V.H / (N.H N.V) kept with visible-normal samples: the weight must divide by the density the samples were drawn from
float mistakeGeometry(float NdotX, float roughness)
{
    float x = max(NdotX, 0.0);
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    return x / (x * (1.0 - k) + k);
}

vec3 specularIBLVisible(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = max(dot(N, V), 1e-4);
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleVNDF(hammersley(i, n), N, V, roughness);
        float VdotH = max(dot(V, H), 0.0);
        vec3 L = 2.0 * VdotH * H - V;
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            float G = mistakeGeometry(NdotV, roughness) * mistakeGeometry(NdotL, roughness);
            float NdotH = max(dot(N, H), 1e-4);
            sum += textureLod(uEnvironment, L, 0.0).rgb * fresnelSchlick(VdotH, F0) *
                   (G * VdotH / (NdotH * NdotV));
        }
    }
    return sum / float(n);
}
