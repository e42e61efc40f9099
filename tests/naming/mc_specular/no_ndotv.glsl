// expect: N.V in the weight G V.H / (N.H N.V) missing
// The weight f (N.L) / pdf without its division by N.V.
vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    uint count = max(sampleCount, 1u);
    float k = roughness * roughness / 2.0;
    float nv = max(dot(N, V), 1e-4);
    vec3 total = vec3(0.0);
    for (uint i = 0u; i < count; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, count), N, roughness);
        vec3 L = reflect(-V, H);
        float nl = dot(N, L);
        if (nl <= 0.0) continue;
        float vh = max(dot(V, H), 0.0);
        float nh = max(dot(N, H), 1e-4);
        float G = (nv / (nv * (1.0 - k) + k)) * (nl / (nl * (1.0 - k) + k));
        vec3 F = fresnelSchlick(vh, F0);
        total += textureLod(uEnvironment, L, 0.0).rgb * F * G * vh / nh;
    }
    return total / float(count);
}
