// What this step shows: F0 as a colour on the sphere. Dielectric areas (metallic 0) are a flat
// dark grey, 0.04; metal plates (metallic 1) show their albedo, the tint of their reflection.
vec3 view(Surface s)
{
    return baseReflectivity(s.albedo, s.metallic);
}
