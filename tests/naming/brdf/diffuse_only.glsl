// expect: without the specular term
// The specular lobe forgotten.
vec3 cookTorranceBRDF(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float roughness)
{
    vec3 F0 = mix(vec3(0.04), albedo, metallic);
    vec3 H = normalize(L + V);
    vec3 F = fresnelSchlick(max(dot(H, V), 0.0), F0);
    vec3 kD = (vec3(1.0) - F) * (1.0 - metallic);
    return kD * albedo / PI;
}
