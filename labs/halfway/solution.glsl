// Only microfacets whose normal bisects the light and view directions mirror light into the
// eye; that normal is the half vector. When V = -L no such facet exists: return the zero
// vector, for which the later terms (D, F) still give finite values.
vec3 halfwayVector(vec3 L, vec3 V)
{
    // BEGIN SOLUTION
    return pbrlab_safeNormalize(L + V, vec3(0.0));
    // END SOLUTION
}
