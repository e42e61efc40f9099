// correct: the lesson's two-line form
vec3 baseReflectivity(vec3 albedo, float metallic)
{
    vec3 F0 = vec3(0.04);
    F0 = mix(F0, albedo, metallic);
    return F0;
}
