// expect: the light's colour / (1 + 0.09 d + 0.032 d^2)
// mistake: the non-physical constant-linear-quadratic attenuation of the Phong lessons
vec3 pointLightRadiance(vec3 lightColor, vec3 lightPos, vec3 worldPos)
{
    float d = length(lightPos - worldPos);
    return lightColor / (1.0 + 0.09 * d + 0.032 * d * d);
}
