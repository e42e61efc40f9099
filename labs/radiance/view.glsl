// What this step shows: the radiance arriving from the light at each point of the sphere, before
// any cosine or BRDF. The light is about 10 units away, so the point nearest to it (upper
// right) gets only ~35% more than the far rim: a light grey, slightly brighter towards the light.
vec3 view(Surface s)
{
    return pointLightRadiance(s.lightColor, s.lightPosition, s.position);
}
