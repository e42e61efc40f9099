// What this step shows: E(N.V), the share of the light a white metal returns in the white
// furnace, in false colour (1: all of it). Smooth spheres keep everything but a thin rim; rough
// ones lose light everywhere, most at grazing view. E_avg is the second value (not drawn).
vec3 view(Surface s)
{
    return vec3(directionalAlbedo(clamp(dot(s.normal, s.view), 0.0, 1.0), s.roughness), 0.0);
}
