// expect: the LUT's bias B
// mistake: E = A, the LUT's scale alone; with F0 = 1 the specular reflectance is F0 A + B = A + B
vec2 directionalAlbedo(float NdotV, float roughness)
{
    float E = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).r;
    float sum = 0.0;
    for (int i = 0; i < 256; ++i) {
        float mu = (float(i) + 0.5) / 256.0;
        sum += textureLod(uBrdfLut, vec2(mu, roughness), 0.0).r * mu;
    }
    return vec2(E, sum / 128.0);
}
