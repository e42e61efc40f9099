// expect: the reference times N.L
// mistake: the cosine N.L multiplied into the BRDF (it belongs to the reflectance equation)
vec3 cookTorranceBRDF(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 H = halfwayVector(L, V);
    vec3 F = fresnelSchlick(max(dot(H, V), 0.0), F0);
    vec3 kD = (vec3(1.0) - F) * (1.0 - metallic);
    vec3 f = kD * albedo / PI + cookTorranceSpecular(N, V, L, F0, roughness);
    return f * max(dot(N, L), 0.0);
}
