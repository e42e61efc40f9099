// expect: applied to the diffuse part too
// mistake: the whole BRDF scaled by the compensation: it gives back light lost by the specular lobe, not by the diffuse part
vec3 cookTorranceBRDFMultiscatter(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 F = fresnelSchlick(max(dot(halfwayVector(L, V), V), 0.0), F0);
    vec3 kD = (1.0 - F) * (1.0 - metallic);
    vec2 AB = textureLod(uBrdfLut, vec2(max(dot(N, V), 0.0), roughness), 0.0).rg;
    float E = AB.x + AB.y;
    vec3 compensation = 1.0 + F0 * (1.0 / E - 1.0);
    return (kD * albedo / PI + cookTorranceSpecular(N, V, L, F0, roughness)) * compensation;
}
