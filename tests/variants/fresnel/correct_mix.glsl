// correct: written as a blend from F0 towards white
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    return mix(F0, vec3(1.0), pow(1.0 - max(cosTheta, 0.0), 5.0));
}
