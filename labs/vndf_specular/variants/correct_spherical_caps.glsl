// A correct variant: its own sampler, the spherical caps of Dupuy and Benyoub 2023, in a frame
// of its own, and G1(V) through Smith's Lambda: 1 / (1 + Lambda), Lambda = (sqrt(1 + a^2 t^2) - 1) / 2.
float ownSchlickGGX(float NdotX, float roughness)
{
    float x = max(NdotX, 0.0);
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    return x / (x * (1.0 - k) + k);
}

vec3 specularIBLVisible(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    float NdotV = max(dot(N, V), 1e-4);
    float a = max(roughness * roughness, 3.1622777e-4);
    float lambda = 0.5 * (sqrt(1.0 + a * a * (1.0 - NdotV * NdotV) / (NdotV * NdotV)) - 1.0);
    float G1v = 1.0 / (1.0 + lambda);
    vec3 B = normalize(abs(N.x) > 0.5 ? cross(N, vec3(0.0, 1.0, 0.0)) : cross(N, vec3(1.0, 0.0, 0.0)));
    vec3 T = cross(B, N);
    vec3 Vh = normalize(vec3(a * dot(V, T), a * dot(V, B), NdotV));
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec2 u = hammersley(i, n);
        float phi = 2.0 * PI * u.x;
        float z = (1.0 - u.y) * (1.0 + Vh.z) - Vh.z;
        float sinTheta = sqrt(clamp(1.0 - z * z, 0.0, 1.0));
        vec3 Hh = vec3(sinTheta * cos(phi), sinTheta * sin(phi), z) + Vh;
        vec3 He = normalize(vec3(a * Hh.xy, max(Hh.z, 0.0)));
        vec3 H = normalize(T * He.x + B * He.y + N * He.z);
        float VdotH = max(dot(V, H), 0.0);
        vec3 L = reflect(-V, H);
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            float G = ownSchlickGGX(NdotV, roughness) * ownSchlickGGX(NdotL, roughness);
            sum += textureLod(uEnvironment, L, 0.0).rgb * fresnelSchlick(VdotH, F0) * G / G1v;
        }
    }
    return sum / float(n);
}
