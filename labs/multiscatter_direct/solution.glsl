// The Cook-Torrance BRDF of step `brdf` with the energy of multiple scattering given back to
// its specular lobe (Turquin 2019, "Practical multiple scattering compensation for microfacet
// models"). The lobe keeps E(N.V) = A + B of white light (step `furnace`); the light that
// bounced more than once would, summed, make a white metal keep all of it. Scaling the lobe by
// 1 / E does that for F0 = 1; for other F0 the bounces keep less, and the scale is
//     1 + F0 (1 - E) / E  =  1 + F0 (1 / E - 1),
// with E read from the LUT at the view direction. The diffuse part is unchanged.
vec3 cookTorranceBRDFMultiscatter(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    // BEGIN SOLUTION
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 H = halfwayVector(L, V);
    vec3 F = fresnelSchlick(max(dot(H, V), 0.0), F0);
    vec3 kD = (1.0 - F) * (1.0 - metallic);
    vec2 AB = textureLod(uBrdfLut, vec2(max(dot(N, V), 0.0), roughness), 0.0).rg;
    float E = AB.x + AB.y;
    vec3 compensation = 1.0 + F0 * (1.0 / E - 1.0);
    return kD * albedo / PI + cookTorranceSpecular(N, V, L, F0, roughness) * compensation;
    // END SOLUTION
}
