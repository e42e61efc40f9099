// expect: (alpha^2)^2 in the numerator
// The numerator squared once more than the formula: alpha^4 on top.
float distributionGGX(vec3 N, vec3 H, float roughness)
{
    float a = roughness * roughness;
    float a2 = max(a * a, 1e-7);
    float NdotH = max(dot(N, H), 0.0);
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return (a2 * a2) / (PI * d * d);
}
