// A correct variant: E_avg by the trapezoid rule on 65 nodes from mu = 0 to 1 (the ends
// included, half weight), E at the given N.V as the solution reads it.
vec2 directionalAlbedo(float NdotV, float roughness)
{
    vec2 AB = texture(uBrdfLut, vec2(NdotV, roughness)).rg;
    float sum = 0.0;
    for (int i = 0; i <= 64; ++i) {
        float mu = float(i) / 64.0;
        vec2 ab = texture(uBrdfLut, vec2(mu, roughness)).rg;
        float w = (i == 0 || i == 64) ? 0.5 : 1.0;
        sum += w * (ab.r + ab.g) * mu;
    }
    return vec2(AB.r + AB.g, 2.0 * sum / 64.0);
}
