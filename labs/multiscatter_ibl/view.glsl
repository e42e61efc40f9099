// What this step shows: each surface lit only by the environment, as in step `split_sum`, with
// the light of multiple scattering given back. Rough metals are brighter than split_sum's and
// keep their colour saturated (each bounce tints it again); smooth ones hardly change.
vec3 view(Surface s)
{
    return ambientIBLMultiscatter(s.normal, s.view, s.albedo, s.metallic, s.roughness, s.ao) +
           s.emissive;
}
