// expect: taken as the average (L + V) / 2
// mistake: "halfway" taken as the average (L + V) / 2, which is not a unit vector
vec3 halfwayVector(vec3 L, vec3 V)
{
    return (L + V) * 0.5;
}
