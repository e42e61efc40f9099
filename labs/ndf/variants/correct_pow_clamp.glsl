// correct: pow() for the squares, clamp() on N.H, other floor (1e-6) on alpha^2
float distributionGGX(vec3 N, vec3 H, float roughness)
{
    float alpha = roughness * roughness;
    float a2 = max(pow(alpha, 2.0), 1e-6);
    float cosH = clamp(dot(N, H), 0.0, 1.0);
    float t = cosH * cosH * (a2 - 1.0) + 1.0;
    return a2 / (PI * pow(t, 2.0));
}
