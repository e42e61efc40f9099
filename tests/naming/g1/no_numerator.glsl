// expect: N.X in the numerator missing
// The numerator N.X forgotten: only the reciprocal of the denominator.
float geometrySchlickGGX(float NdotX, float roughness)
{
    float k = (roughness + 1.0) * (roughness + 1.0) * 0.125;
    float x = max(NdotX, 0.0);
    return 1.0 / (x - x * k + k);
}
