// expect: (roughness, N.V)
// mistake: the LUT read at (roughness, N.V) instead of (N.V, roughness)
vec3 cookTorranceBRDFMultiscatter(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 F = fresnelSchlick(max(dot(halfwayVector(L, V), V), 0.0), F0);
    vec3 kD = (1.0 - F) * (1.0 - metallic);
    vec2 AB = textureLod(uBrdfLut, vec2(roughness, max(dot(N, V), 0.0)), 0.0).rg;
    float E = AB.x + AB.y;
    return kD * albedo / PI + cookTorranceSpecular(N, V, L, F0, roughness) * (1.0 + F0 * (1.0 / E - 1.0));
}
