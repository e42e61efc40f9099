// expect: 1/d^3 where the reference has 1/d^2
// The light falls off with the cube of the distance.
vec3 pointLightRadiance(vec3 lightColor, vec3 lightPos, vec3 worldPos)
{
    float dist = max(distance(lightPos, worldPos), 0.01);
    return lightColor / (dist * dist * dist);
}
