// expect: mix arguments reversed
// mistake: mix arguments reversed (dielectrics get the albedo, metals get 0.04)
vec3 baseReflectivity(vec3 albedo, float metallic)
{
    return mix(albedo, vec3(0.04), metallic);
}
