// What this step shows: H as a colour (0.5 + 0.5 H). The light is up and to the right, the
// camera on +z, so H leans up and right: bluish, from violet at the upper left to light blue
// at the lower right (V turns across the sphere, L barely changes).
vec3 view(Surface s)
{
    return halfwayVector(s.light, s.view);
}
