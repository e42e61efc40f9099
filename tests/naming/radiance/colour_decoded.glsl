// expect: the light's colour applied twice
// The light's colour "decoded" by squaring it, as if it were display-encoded.
vec3 pointLightRadiance(vec3 lightColor, vec3 lightPos, vec3 worldPos)
{
    vec3 intensity = lightColor * lightColor;
    float r = length(lightPos - worldPos);
    return intensity / max(r * r, 1e-4);
}
