// expect: the reference divided by G1(N.L)
// mistake: only one Schlick-GGX term (masking) instead of Smith's product
vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)
{
    vec3 H = halfwayVector(L, V);
    float D = distributionGGX(N, H, roughness);
    float G = geometrySchlickGGX(max(dot(N, V), 0.0), roughness);
    vec3 F = fresnelSchlick(max(dot(H, V), 0.0), F0);
    return D * G * F / max(4.0 * max(dot(N, V), 0.0) * max(dot(N, L), 0.0), 1e-4);
}
