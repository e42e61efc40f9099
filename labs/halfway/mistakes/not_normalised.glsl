// expect: the half vector is not normalised
// mistake: the half vector is not normalised (length up to 2)
vec3 halfwayVector(vec3 L, vec3 V)
{
    return L + V;
}
