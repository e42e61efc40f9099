// What this step shows: the sphere lit by the whole environment through a white Lambertian
// surface, E(N) / PI per pixel (no point lights, no texture), with the sky drawn behind. The
// sun (up, right, behind the camera) makes the side facing it bright and warm; the opposite
// side gets only the blue sky and the dim ground, and the lower half is tinted by the ground.
vec3 view(Surface s)
{
    return irradianceAt(s.normal);
}
