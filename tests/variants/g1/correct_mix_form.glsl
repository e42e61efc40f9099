// correct: denominator written as mix(k, 1, x), clamp instead of max, pow for the square
float geometrySchlickGGX(float NdotX, float roughness)
{
    float x = clamp(NdotX, 0.0, 1.0);
    float k = pow(roughness + 1.0, 2.0) * 0.125;
    return x / mix(k, 1.0, x);
}
