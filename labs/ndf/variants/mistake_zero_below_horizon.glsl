// expect: yours is 0 where N.H <= 0, the reference is not
// mistake: D = 0 where N.H <= 0 (Walter et al. 2007 write D with the characteristic function
// chi+(N.H)); the contract's D is max(N.H, 0) in the formula, so a2 / PI there, not 0
float distributionGGX(vec3 N, vec3 H, float roughness)
{
    float NdotH = dot(N, H);
    if (NdotH <= 0.0) return 0.0;
    float a = roughness * roughness;
    float a2 = a * a;
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}
