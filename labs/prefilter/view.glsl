// What this step shows: the environment seen in each sphere's mirror direction
// R = reflect(-V, N), blurred by the GGX lobe of the sphere's roughness (columns: 0.05 on the
// left to 0.86 on the right; the rows repeat, metallic plays no part here). No Fresnel, no
// BRDF scale: this is the radiance the split sum multiplies by the LUT's F0 A + B. The sun
// sits behind the camera, up and to the right: a sharp dot on the smooth spheres; on the rough
// ones, one bright speckle per sample that hits it (64 by default; more samples merge them).

vec3 view(Surface s)
{
    vec3 R = reflect(-s.view, s.normal);
    return prefilterEnvironment(R, s.roughness, uint(max(u_samples, 1)));
}
