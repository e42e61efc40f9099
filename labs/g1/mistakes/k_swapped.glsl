// expect: k and (1 - k) swapped
// mistake: k and (1 - k) swapped in the denominator
float geometrySchlickGGX(float NdotX, float roughness)
{
    float r = roughness + 1.0;
    float k = r * r / 8.0;
    float x = max(NdotX, 0.0);
    return x / (x * k + (1.0 - k));
}
