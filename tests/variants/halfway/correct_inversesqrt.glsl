// correct: inversesqrt of the squared length, guarded with max()
vec3 halfwayVector(vec3 L, vec3 V)
{
    vec3 h = L + V;
    return h * inversesqrt(max(dot(h, h), 1e-20));
}
