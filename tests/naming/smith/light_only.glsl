// expect: the masking term G1(N.V) missing
// Only the shadowing towards the light; the masking towards the viewer forgotten.
float geometrySmith(vec3 N, vec3 V, vec3 L, float roughness)
{
    float cosL = max(dot(L, N), 0.0);
    return geometrySchlickGGX(cosL, roughness);
}
