// expect: fits the reference without (1 - F0)
// mistake: the (1 - F0) factor is missing, reflectance can exceed 1
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    return F0 + pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}
