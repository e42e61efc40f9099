// mistake: (1 - cosTheta) not clamped; its callers pass max(dot(H, V), 0.0), which is 1 + 1 ulp
// when V = L, and pow of a negative base is NaN (LearnOpenGL clamps here for this reason)
// expect: NaN on an input its callers produce
vec3 fresnelSchlick(float cosTheta, vec3 F0)
{
    return F0 + (1.0 - F0) * pow(1.0 - cosTheta, 5.0);
}
