// A correct variant: E_avg summed at the LUT's own texel centres, as many nodes as the LUT is
// wide (textureSize), so it follows whatever size the host gives the LUT.
vec2 directionalAlbedo(float NdotV, float roughness)
{
    float E = dot(textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).rg, vec2(1.0));
    int width = textureSize(uBrdfLut, 0).x;
    float average = 0.0;
    for (int i = 0; i < width; ++i) {
        float mu = (float(i) + 0.5) / float(width);
        average += dot(textureLod(uBrdfLut, vec2(mu, roughness), 0.0).rg, vec2(1.0)) * 2.0 * mu;
    }
    return vec2(E, average / float(width));
}
