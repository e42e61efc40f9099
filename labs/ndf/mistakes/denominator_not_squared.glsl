// expect: fits the denominator to the power 1 where the reference has the denominator to the power 2
// mistake: the bracket in the denominator is not squared
float distributionGGX(vec3 N, vec3 H, float roughness)
{
    float a = roughness * roughness;
    float a2 = a * a;
    float NdotH = max(dot(N, H), 0.0);
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (PI * d);
}
