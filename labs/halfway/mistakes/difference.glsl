// expect: -V in place of V
// mistake: sign error, normalize(L - V) (one vector taken pointing into the surface)
vec3 halfwayVector(vec3 L, vec3 V)
{
    return normalize(L - V);
}
