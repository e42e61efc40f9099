// expect: whatever the inputs
// mistake: no attenuation at all (treated like a directional light)
vec3 pointLightRadiance(vec3 lightColor, vec3 lightPos, vec3 worldPos)
{
    return lightColor;
}
