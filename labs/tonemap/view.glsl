// What this step shows: the final picture of the direct lab, the sphere's reflected radiance
// (step `reflectance`) display-encoded: the same image as step `reflectance`'s HDR view, now made by your function.
// The probe (and the stability sweep) hand their HDR input over in s.extra instead: a
// non-zero extra means "tonemap this value" (denormals count as zero, flushed or not).
vec3 view(Surface s)
{
    vec3 hdr = any(greaterThanEqual(abs(s.extra), vec4(1.17549435e-38)))
                   ? s.extra.xyz
                   : reflectedRadiance(s.position, s.normal, s.view, s.albedo, s.metallic,
                                       s.roughness, s.ao) +
                         s.emissive;
    return displayEncode(hdr);
}
