// expect: 1/d^4 where the reference has 1/d^2
// dot(v, v) is already the squared distance; squaring it again gives 1/d^4.
vec3 pointLightRadiance(vec3 lightColor, vec3 lightPos, vec3 worldPos)
{
    vec3 toLight = lightPos - worldPos;
    float d2 = max(dot(toLight, toLight), 1e-4);
    float falloff = 1.0 / (d2 * d2);
    return falloff * lightColor;
}
