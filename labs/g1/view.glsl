// What this step shows: G1 towards the camera (masking), with the plates' roughness map. White
// (1) where the sphere faces the camera, darkening to black at the silhouette, sooner on
// rough plates.
vec3 view(Surface s)
{
    return vec3(geometrySchlickGGX(max(dot(s.normal, s.view), 0.0), s.roughness));
}
