// What this step shows: the BRDF f_r with multiple scattering, on the sphere, as HDR colour
// (Reinhard + gamma), as step `brdf` shows f_r without it. Rough metal plates keep a brighter,
// wider highlight (on the roughest gold plate, about three times brdf's); smooth plates and
// painted ones hardly change. The value fades to 0 over the thin band where 4 N.V N.L < 0.1,
// as brdf's (the specular denominator's guard decides it there).
vec3 view(Surface s)
{
    float band = pbrlab_grazingBand(s.normal, s.view, s.light);
    return band *
           cookTorranceBRDFMultiscatter(s.normal, s.view, s.light, s.albedo, s.metallic, s.roughness);
}
