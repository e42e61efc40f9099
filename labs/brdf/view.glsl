// What this step shows: the BRDF f_r on the sphere, as HDR colour (Reinhard + gamma). Where the
// light is above the horizon the painted plates show their albedo through the diffuse term,
// evenly, with no falloff (f_r has no cosine), plus the highlight; the metal plates are dark
// (no diffuse term) outside the highlight. The value fades to 0 over the thin band where
// 4 N·V N·L < 0.1 and is 0 where N·L <= 0 (f_r is not evaluated for light from below): in that
// band the specular term is decided by the denominator's guard, which legitimately differs
// between solutions (+0.001, max(d, 1e-4)); the stability sweep checks it.
vec3 view(Surface s)
{
    float band = pbrlab_grazingBand(s.normal, s.view, s.light);
    return band * cookTorranceBRDF(s.normal, s.view, s.light, s.albedo, s.metallic, s.roughness);
}
