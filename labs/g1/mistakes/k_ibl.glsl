// expect: k = roughness^2 / 2, where the direct-light remapping is k = (roughness + 1)^2 / 8
// mistake: k = roughness^2 / 2, the remapping for IBL, used for direct light
float geometrySchlickGGX(float NdotX, float roughness)
{
    float k = roughness * roughness / 2.0;
    float x = max(NdotX, 0.0);
    return x / (x * (1.0 - k) + k + 1e-4);
}
