// correct: explicit test for light below the surface
float lambertCosine(vec3 N, vec3 L)
{
    float c = dot(L, N);
    return c > 0.0 ? c : 0.0;
}
