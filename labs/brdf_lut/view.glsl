// What this step shows: the LUT's value (scale A in red, bias B in green) at each pixel's N·V
// and roughness. Where the sphere faces the camera, A is high and B near 0: red, darker on
// the rougher spheres (right; masking). At the silhouette (N·V -> 0) Fresnel moves the weight
// into B: a thin yellow-green rim on the smooth spheres. N·V is floored at 1e-3 (see the
// handout): guards between 1e-4 and 1e-3 inside integrateBRDF then give the same value.

vec3 view(Surface s)
{
    float NdotV = max(dot(s.normal, s.view), 1e-3);
    return vec3(integrateBRDF(NdotV, s.roughness, uint(max(u_samples, 1))), 0.0);
}
