// expect: alpha = roughness^4 where the reference has alpha = roughness^2
// Squares once too often: alpha^2 = roughness^8.
float distributionGGX(vec3 N, vec3 H, float roughness)
{
    float alpha = roughness * roughness;
    alpha = alpha * alpha;
    float alphaSq = max(alpha * alpha, 1e-7);
    float cosH = max(dot(N, H), 0.0);
    float t = cosH * cosH * (alphaSq - 1.0) + 1.0;
    return alphaSq / (PI * t * t);
}
