// Schlick-GGX masking: the fraction of microfacets seen from a direction at cosine NdotX
// that are not hidden by neighbouring facets. Rougher surfaces and grazing directions hide
// more. For direct light k = (roughness + 1)^2 / 8 (Karis' remapping).
float geometrySchlickGGX(float NdotX, float roughness)
{
    // BEGIN SOLUTION
    float x = max(NdotX, 0.0);
    float r = roughness + 1.0;
    float k = r * r / 8.0;
    return x / (x * (1.0 - k) + k);
    // END SOLUTION
}
