// expect: k = roughness / 2, where
// k written as half the roughness.
float geometrySchlickGGX(float NdotX, float roughness)
{
    float k = 0.5 * roughness;
    float n = max(NdotX, 0.0);
    return n / mix(k, 1.0, n);
}
