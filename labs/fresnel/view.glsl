// What this step shows: the Fresnel reflectance F as a colour, for F0 = baseReflectivity(albedo,
// metallic). With u_cosine = N·V (default) every surface brightens towards white at the rim,
// where the view grazes it, dielectric areas most visibly (from 0.04); with H·V (what the
// BRDF uses) F stays close to F0 unless the light moves behind the sphere (V close to -L).

vec3 view(Surface s)
{
    float c = u_cosine == 1 ? max(dot(halfwayVector(s.light, s.view), s.view), 0.0)
                            : max(dot(s.normal, s.view), 0.0);
    return fresnelSchlick(c, baseReflectivity(s.albedo, s.metallic));
}
