// expect: the denominator 4 N.L N.V missing
// The numerator D G F alone.
vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)
{
    vec3 H = halfwayVector(L, V);
    return fresnelSchlick(max(dot(H, V), 0.0), F0) * distributionGGX(N, H, roughness) *
           geometrySmith(N, V, L, roughness);
}
