// expect: Your value is (L + V) / 2, where the reference is normalize(L + V)
// mistake: "halfway" taken as the average (L + V) / 2, which is not a unit vector
vec3 halfwayVector(vec3 L, vec3 V)
{
    return (L + V) * 0.5;
}
