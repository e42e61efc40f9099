// expect: (N.H)^1 in the denominator
// N.H enters the denominator without its square.
float distributionGGX(vec3 N, vec3 H, float roughness)
{
    float r2 = roughness * roughness;
    float a2 = max(r2 * r2, 1e-7);
    float nh = clamp(dot(N, H), 0.0, 1.0);
    float denom = nh * (a2 - 1.0) + 1.0;
    denom = PI * denom * denom;
    return a2 / denom;
}
