// expect: k = (roughness + 1)^2 / 2, where
// Divides by 2 instead of 8.
float geometrySchlickGGX(float NdotX, float roughness)
{
    float rp1 = roughness + 1.0;
    float k = rp1 * rp1 / 2.0;
    float x = max(NdotX, 0.0);
    return x / (x * (1.0 - k) + k);
}
