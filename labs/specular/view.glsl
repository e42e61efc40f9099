// What this step shows: the specular lobe on the sphere, for F0 = baseReflectivity(albedo,
// metallic), in false colour over 1e-3..1e3 (log; red channel). A bright highlight where H
// meets N, tight and intense on smooth plates, wide and dim on rough ones; brighter over the
// metal plates (F0 up to 1) than over the dielectric parts (0.04); zero where N·L <= 0.
// In the thin band where 4 N·V N·L < 0.1 (terminator, silhouette) the value fades to 0: there
// it is decided by the denominator's guard, which legitimately differs between solutions
// (+0.001, max(d, 1e-4)); the stability sweep checks that band.
vec3 view(Surface s)
{
    float band = pbrlab_grazingBand(s.normal, s.view, s.light);
    return band * cookTorranceSpecular(s.normal, s.view, s.light,
                                       baseReflectivity(s.albedo, s.metallic), s.roughness);
}
