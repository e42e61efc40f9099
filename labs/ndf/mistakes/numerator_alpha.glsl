// expect: fits (alpha^2)^0.5 in the numerator
// mistake: numerator alpha instead of alpha^2
float distributionGGX(vec3 N, vec3 H, float roughness)
{
    float a = roughness * roughness;
    float a2 = a * a;
    float NdotH = max(dot(N, H), 0.0);
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a / (PI * d * d);
}
