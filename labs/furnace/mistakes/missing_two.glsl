// expect: is the 2 of E_avg
// mistake: E_avg without the 2 of 2 mu dmu: the cosine-weighted measure is not normalised
vec2 directionalAlbedo(float NdotV, float roughness)
{
    vec2 AB = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).rg;
    float sum = 0.0;
    for (int i = 0; i < 256; ++i) {
        float mu = (float(i) + 0.5) / 256.0;
        vec2 ab = textureLod(uBrdfLut, vec2(mu, roughness), 0.0).rg;
        sum += (ab.x + ab.y) * mu;
    }
    return vec2(AB.x + AB.y, sum / 256.0);
}
