// correct: written as a blend from F0 towards white, 1 - cosTheta floored at 0 (cosTheta
// reaches 1 + 1 ulp, never below 0: its callers pass max(..., 0.0))
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    return mix(F0, vec3(1.0), pow(max(1.0 - cosTheta, 0.0), 5.0));
}
