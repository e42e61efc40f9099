// correct: plain normalize(L + V) without a guard (NaN only when V = -L)
vec3 halfwayVector(vec3 L, vec3 V)
{
    return normalize(L + V);
}
