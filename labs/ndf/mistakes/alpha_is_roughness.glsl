// expect: fits alpha = roughness^1 where the reference has alpha = roughness^2
// mistake: alpha = roughness (perceptual roughness not squared)
float distributionGGX(vec3 N, vec3 H, float roughness)
{
    float a2 = roughness * roughness;
    float NdotH = max(dot(N, H), 0.0);
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}
