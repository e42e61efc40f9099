// The white furnace: how much light the single-scattering GGX lobe keeps. In an environment of
// radiance 1 everywhere, a white metal (F0 = 1) returns its directional albedo
//     E(mu) = integral of f(l, v) (N.L) dl = A + B,
// the split-sum LUT's two channels at (mu = N.V, roughness) with F0 = 1. Over all directions
// of incidence, the cosine-weighted average is
//     E_avg = 2 * integral from 0 to 1 of E(mu) mu dmu,
// (the hemisphere's cosine-weighted measure, normalised: 2 mu dmu integrates to 1).
// Returns vec2(E(NdotV), E_avg(roughness)).
vec2 directionalAlbedo(float NdotV, float roughness)
{
    // BEGIN SOLUTION
    vec2 AB = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).rg;
    // E_avg by the midpoint rule in mu, 256 nodes: the LUT is piecewise linear in mu between
    // its 1024 texel centres, and this sum is within 2e-5 of its exact integral.
    const int n = 256;
    float sum = 0.0;
    for (int i = 0; i < n; ++i) {
        float mu = (float(i) + 0.5) / float(n);
        vec2 ab = textureLod(uBrdfLut, vec2(mu, roughness), 0.0).rg;
        sum += (ab.x + ab.y) * mu;
    }
    return vec2(AB.x + AB.y, 2.0 * sum / float(n));
    // END SOLUTION
}
