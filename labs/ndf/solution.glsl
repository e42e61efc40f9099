// Normal distribution function (Trowbridge-Reitz GGX): the density of microfacet normals
// aligned with H, so that D(h) (n.h) integrates to 1 over the hemisphere. alpha = roughness^2;
// alpha^2 is floored at 1e-7 so a perfect mirror (roughness 0) gives a tall, finite peak.
float distributionGGX(vec3 N, vec3 H, float roughness)
{
    // BEGIN SOLUTION
    float a = roughness * roughness;
    float a2 = max(a * a, 1e-7);
    float NdotH = max(dot(N, H), 0.0);
    float NdotH2 = NdotH * NdotH;
    // Same as NdotH2 * (a2 - 1.0) + 1.0, grouped so nothing cancels at NdotH = 1 in float.
    float d = (1.0 - NdotH2) + NdotH2 * a2;
    return a2 / (PI * d * d);
    // END SOLUTION
}
