// mistake: the environment read at mip 1 (a copy blurred over 2 x 2 texels) instead of mip 0.
// Fails by the value band alone (test_variants.cpp, mistake_band_*): the blur changes the
// value where the sky has detail finer than a mip-1 texel, the sun at low roughness, which the
// probe crosses and few random inputs reach; its error there has no sign that holds over a
// region of the random inputs, the error still falls with the count, it is linear in radiance.
// expect: wrong only where roughness <
float pbrlab_mcGeometrySchlickGGX(float NdotX, float roughness)
{
    float x = max(NdotX, 0.0);
    float k = max(roughness * roughness, 3.1622777e-4) * 0.5;
    return x / (x * (1.0 - k) + k);
}

vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)
{
    // N.V floored: it divides the weight (1e-4 as in the LUT).
    float NdotV = max(dot(N, V), 1e-4);
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        float VdotH = dot(V, H);
        vec3 L = 2.0 * VdotH * H - V;
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            // N.H floored (it divides); V.H clamped (V below the horizon can make it < 0).
            float NdotH = max(dot(N, H), 1e-4);
            VdotH = max(VdotH, 0.0);
            float G = pbrlab_mcGeometrySchlickGGX(NdotV, roughness) *
                      pbrlab_mcGeometrySchlickGGX(NdotL, roughness);
            vec3 F = fresnelSchlick(VdotH, F0);
            sum += textureLod(uEnvironment, L, 1.0).rgb * F * (G * VdotH / (NdotH * NdotV));
        }
    }
    return sum / float(n);
}
