// correct: Walter et al.'s form alpha^2 / (PI cos^4 (alpha^2 + tan^2)^2)
float distributionGGX(vec3 N, vec3 H, float roughness)
{
    float alpha2 = pow(roughness, 4.0);
    float c2 = max(dot(N, H), 0.0);
    c2 = max(c2 * c2, 1e-6);
    float tan2 = (1.0 - c2) / c2;
    float s = alpha2 + tan2;
    return alpha2 / (PI * c2 * c2 * s * s);
}
