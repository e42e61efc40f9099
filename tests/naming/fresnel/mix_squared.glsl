// expect: (1 - cos)^2 where
// Written as a mix towards white with the wrong exponent.
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    float t = clamp(1.0 - cosTheta, 0.0, 1.0);
    return mix(F0, vec3(1.0), t * t);
}
