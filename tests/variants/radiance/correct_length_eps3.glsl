// correct: inverse square from length(), other floor (1e-3) on the squared distance
vec3 pointLightRadiance(vec3 lightColor, vec3 lightPos, vec3 worldPos)
{
    float dist = length(lightPos - worldPos);
    return lightColor * (1.0 / max(dist * dist, 1e-3));
}
