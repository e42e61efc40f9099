// What this step shows: the shaded sphere, HDR radiance through Reinhard + gamma. The plates
// lit from the upper right, a highlight there (tight on smooth plates), metal plates darker
// than painted ones except in the highlight, crevices darker (ao) and the side turned away
// from the light lit only by the faint ambient term.
// Emitting surfaces (glTF emissive) add their own light on top: not part of your function.
vec3 view(Surface s)
{
    return reflectedRadiance(s.position, s.normal, s.view, s.albedo, s.metallic, s.roughness,
                             s.ao) +
           s.emissive;
}
