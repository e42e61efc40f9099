// What this step shows: D for the half vector between light and camera, with the plates'
// roughness map. A bright lobe where N·H = 1 (up and right, between the light and the eye),
// tight and tall on smooth plates, wide and low on rough ones (log colour scale).
vec3 view(Surface s)
{
    return vec3(distributionGGX(s.normal, halfwayVector(s.light, s.view), s.roughness));
}
