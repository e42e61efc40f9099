// expect: G1(N.L) for the view too
// Copy-paste slip: N.L used for both factors.
float geometrySmith(vec3 N, vec3 V, vec3 L, float roughness)
{
    float shadowing = geometrySchlickGGX(max(dot(N, L), 0.0), roughness);
    float masking = geometrySchlickGGX(max(dot(N, L), 0.0), roughness);
    return masking * shadowing;
}
