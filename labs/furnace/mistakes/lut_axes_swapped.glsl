// expect: (roughness, N.V)
// mistake: the LUT read at (roughness, N.V) instead of (N.V, roughness)
vec2 directionalAlbedo(float NdotV, float roughness)
{
    vec2 AB = textureLod(uBrdfLut, vec2(roughness, NdotV), 0.0).rg;
    float sum = 0.0;
    for (int i = 0; i < 256; ++i) {
        float mu = (float(i) + 0.5) / 256.0;
        vec2 ab = textureLod(uBrdfLut, vec2(roughness, mu), 0.0).rg;
        sum += (ab.x + ab.y) * mu;
    }
    return vec2(AB.x + AB.y, sum / 128.0);
}
