// A correct variant: the compensation as one ratio, (E + F0 (1 - E)) / E, the lobe's share
// E plus what the bounces return, over E.
vec3 cookTorranceBRDFMultiscatter(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 F0 = baseReflectivity(albedo, metallic);
    float E = dot(textureLod(uBrdfLut, vec2(clamp(dot(N, V), 0.0, 1.0), roughness), 0.0).rg,
                  vec2(1.0));
    vec3 specular = cookTorranceSpecular(N, V, L, F0, roughness) * (E + F0 * (1.0 - E)) / E;
    vec3 F = fresnelSchlick(max(dot(halfwayVector(L, V), V), 0.0), F0);
    return (vec3(1.0) - F) * (1.0 - metallic) * albedo / PI + specular;
}
