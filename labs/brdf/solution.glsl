// The full BRDF f_r: light not reflected at the surface (1 - F) enters it and leaves
// diffusely (Lambert, albedo / PI), except in metals, which absorb it (factor 1 - metallic).
// The reflected part is the Cook-Torrance specular lobe. Energy is split, never created.
vec3 cookTorranceBRDF(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    // BEGIN SOLUTION
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 H = halfwayVector(L, V);
    vec3 F = fresnelSchlick(max(dot(H, V), 0.0), F0);
    vec3 kD = (1.0 - F) * (1.0 - metallic);
    return kD * albedo / PI + cookTorranceSpecular(N, V, L, F0, roughness);
    // END SOLUTION
}
