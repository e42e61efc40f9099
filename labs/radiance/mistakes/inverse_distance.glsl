// expect: fits 1/d^1 where the reference has 1/d^2
// mistake: 1/d instead of the inverse square 1/d^2
vec3 pointLightRadiance(vec3 lightColor, vec3 lightPos, vec3 worldPos)
{
    float dist = length(lightPos - worldPos);
    return lightColor / max(dist, 1e-2);
}
