// expect: Your value is L + V, where the reference is normalize(L + V)
// mistake: the half vector is not normalised (length up to 2)
vec3 halfwayVector(vec3 L, vec3 V)
{
    return L + V;
}
