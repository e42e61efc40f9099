// expect: F0 where F belongs
// F0 in place of the Fresnel term.
vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = max(dot(N, V), 1e-4);
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    float gv = NdotV / (NdotV * (1.0 - k) + k);
    uint n = max(sampleCount, 1u);
    vec3 radiance = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        vec3 L = normalize(2.0 * dot(V, H) * H - V);
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            float gl = NdotL / (NdotL * (1.0 - k) + k);
            float VdotH = max(dot(V, H), 0.0);
            radiance += textureLod(uEnvironment, L, 0.0).rgb * gv * gl * VdotH /
                        (max(dot(N, H), 1e-4) * NdotV);
        }
    }
    return F0 * radiance / float(n);
}
