// What this step shows: the specular light each sphere reflects from the environment, summed
// sample by sample (no point lights, no diffuse part), with the sky drawn behind. Smooth
// spheres (left) mirror the sky and the ground; rough ones (right) blur them; metals (top
// rows) reflect more and tint it with their red albedo, dielectrics (bottom) reflect 4 %
// head-on and more at the rim (Fresnel). Every pixel uses the same n Hammersley points, so
// few samples (--set samples=4) show as a few overlapping copies of the sky on the rough
// spheres, not as grain; the sun (1.2 degrees, 20000 times brighter than the sky) is found
// by one sample here and there: the bright specks on the rough spheres, which only average
// out after tens of thousands of samples. That is the cost the split sum (steps `prefilter` to `split_sum`) removes.
// Where the interpolated normal turns away from the camera (N·V < 0, a sliver of silhouette
// pixels) V is below the surface and nothing is reflected towards the eye: the view shows 0
// there without calling your function. N·V = 0 itself is evaluated (the stability sweep's
// grazing case).

vec3 view(Surface s)
{
    if (dot(s.normal, s.view) < 0.0) return vec3(0.0);
    vec3 F0 = baseReflectivity(s.albedo, s.metallic);
    return specularIBLReference(s.normal, s.view, F0, s.roughness, uint(max(u_samples, 0)));
}
