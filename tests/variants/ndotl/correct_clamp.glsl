// correct: clamp to [0, 1] instead of max with 0
float lambertCosine(vec3 N, vec3 L)
{
    return clamp(dot(N, L), 0.0, 1.0);
}
