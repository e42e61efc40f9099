// expect: the V.H / (N.H N.V) left after dividing by the pdf missing
// mistake: samples weighted by F G only; the V.H / (N.H N.V) left after dividing by the pdf is
// missing
vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = max(dot(N, V), 1e-4);
    float k = roughness * roughness / 2.0;
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < sampleCount; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, sampleCount), N, roughness);
        vec3 L = reflect(-V, H);
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            float VdotH = max(dot(V, H), 0.0);
            float G = (NdotV / (NdotV * (1.0 - k) + k)) * (NdotL / (NdotL * (1.0 - k) + k));
            sum += textureLod(uEnvironment, L, 0.0).rgb * fresnelSchlick(VdotH, F0) * G;
        }
    }
    return sum / float(sampleCount);
}
