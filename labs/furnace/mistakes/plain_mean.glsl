// expect: the plain mean of E over N.V
// mistake: E_avg as the plain mean of E over N.V, without the cosine weight 2 mu
vec2 directionalAlbedo(float NdotV, float roughness)
{
    vec2 AB = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).rg;
    float sum = 0.0;
    for (int i = 0; i < 256; ++i) {
        float mu = (float(i) + 0.5) / 256.0;
        vec2 ab = textureLod(uBrdfLut, vec2(mu, roughness), 0.0).rg;
        sum += ab.x + ab.y;
    }
    return vec2(AB.x + AB.y, sum / 256.0);
}
