// expect: k = roughness^2, where
// k taken as alpha itself.
float geometrySchlickGGX(float NdotX, float roughness)
{
    float alpha = roughness * roughness;
    float cosine = max(NdotX, 0.0);
    return cosine / (cosine * (1.0 - alpha) + alpha);
}
