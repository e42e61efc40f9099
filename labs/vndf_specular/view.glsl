// What this step shows: the specular light each sphere reflects from the environment, as step
// `mc_specular` shows it, sampled through the visible normals: the same picture, with less
// error at grazing view, where D (N.H) spends samples on normals V cannot see (the handout has
// the figures). Where the interpolated normal turns away from the camera (N·V < 0) nothing is
// reflected towards the eye: 0, without calling your function.
vec3 view(Surface s)
{
    if (dot(s.normal, s.view) < 0.0) return vec3(0.0);
    vec3 F0 = baseReflectivity(s.albedo, s.metallic);
    return specularIBLVisible(s.normal, s.view, F0, s.roughness, uint(max(u_samples, 0)));
}
