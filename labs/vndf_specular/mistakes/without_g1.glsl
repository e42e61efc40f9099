// expect: G1(V)^0 where the reference has
// mistake: the weight F G without the division by G1(V): the density of the visible normals has G1(V) in it
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
            sum += textureLod(uEnvironment, L, 0.0).rgb * fresnelSchlick(VdotH, F0) * G;
        }
    }
    return sum / float(n);
}
