// expect: k = (roughness + 1) / 8, where the direct-light remapping is k = (roughness + 1)^2 / 8
// mistake: k = (roughness + 1) / 8, the square is missing
float geometrySchlickGGX(float NdotX, float roughness)
{
    float k = (roughness + 1.0) / 8.0;
    float x = max(NdotX, 0.0);
    return x / (x * (1.0 - k) + k);
}
