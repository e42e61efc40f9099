// converge: the specular ambient term by Monte Carlo with visible-normal sampling (step
// `vndf_specular`), u_samples samples: the same integral as specular_brute_force.

vec3 view(Surface s)
{
    if (dot(s.normal, s.view) < 0.0) return vec3(0.0);
    vec3 F0 = baseReflectivity(s.albedo, s.metallic);
    return specularIBLVisible(s.normal, s.view, F0, s.roughness, uint(u_samples));
}
