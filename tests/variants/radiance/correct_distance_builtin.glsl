// correct: distance() built-in, attenuation clamped with clamp() instead of max()
vec3 pointLightRadiance(vec3 lightColor, vec3 lightPos, vec3 worldPos)
{
    float dist = distance(worldPos, lightPos);
    float attenuation = 1.0 / clamp(dist * dist, 1e-4, 1e30);
    return attenuation * lightColor;
}
