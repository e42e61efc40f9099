// correct: the lesson's fresnelSchlick (LearnOpenGL), which clamps 1 - cosTheta: its callers
// pass max(dot(H, V), 0.0), which reaches 1 + 1 ulp when V = L
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    return F0 + (1.0 - F0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}
