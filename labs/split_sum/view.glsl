// What this step shows: each sphere lit only by the environment (no point lights), the sky
// drawn behind. Smooth spheres mirror the sky and the ground; rough ones blur it; metals
// (top rows) tint their reflection with the albedo and have no diffuse part.
// Emitting surfaces (glTF emissive) add their own light on top: not part of your function.
vec3 view(Surface s)
{
    return ambientIBL(s.normal, s.view, s.albedo, s.metallic, s.roughness, s.ao) + s.emissive;
}
