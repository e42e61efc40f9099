// What this step shows: G for the camera and the light, with the plates' roughness map. Near 1
// where the sphere faces both, darkening towards the silhouette (masking) and towards the
// terminator (shadowing), black on the side turned away from the light.
vec3 view(Surface s)
{
    return vec3(geometrySmith(s.normal, s.view, s.light, s.roughness));
}
