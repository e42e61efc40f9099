// converge: the specular ambient term by brute-force Monte Carlo (step `mc_specular`), u_samples samples.

vec3 view(Surface s)
{
    vec3 F0 = baseReflectivity(s.albedo, s.metallic);
    return specularIBLReference(s.normal, s.view, F0, s.roughness, uint(u_samples));
}
