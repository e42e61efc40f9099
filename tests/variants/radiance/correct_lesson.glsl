// correct: the lesson's unguarded inverse-square attenuation (infinite at distance 0)
vec3 pointLightRadiance(vec3 lightColor, vec3 lightPos, vec3 worldPos)
{
    float distance = length(lightPos - worldPos);
    float attenuation = 1.0 / (distance * distance);
    return lightColor * attenuation;
}
