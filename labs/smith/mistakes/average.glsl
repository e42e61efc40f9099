// expect: G1(N.V) and G1(N.L) averaged
// mistake: the two G1 terms averaged instead of multiplied
float geometrySmith(vec3 N, vec3 V, vec3 L, float roughness)
{
    float gv = geometrySchlickGGX(max(dot(N, V), 0.0), roughness);
    float gl = geometrySchlickGGX(max(dot(N, L), 0.0), roughness);
    return 0.5 * (gv + gl);
}
