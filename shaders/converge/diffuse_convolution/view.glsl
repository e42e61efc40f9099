// converge: the diffuse ambient term, albedo * E/PI, from the convolved irradiance cube.
vec3 view(Surface s)
{
    return s.albedo * textureLod(uIrradianceMap, s.normal, 0.0).rgb;
}
