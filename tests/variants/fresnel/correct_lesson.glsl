// correct: the lesson's fresnelSchlick, no clamp (cosTheta assumed in [0, 1])
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    return F0 + (1.0 - F0) * pow(1.0 - cosTheta, 5.0);
}
