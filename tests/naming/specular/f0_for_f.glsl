// expect: F0 where F belongs
// F0 used as the Fresnel term, without the angle dependence.
vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)
{
    vec3 H = halfwayVector(L, V);
    float DG = distributionGGX(N, H, roughness) * geometrySmith(N, V, L, roughness);
    float denominator = max(4.0 * max(dot(N, V), 0.0) * max(dot(N, L), 0.0), 1e-4);
    return F0 * DG / denominator;
}
