// expect: IBL remapping
// Schlick-GGX written inline with the IBL remapping k = alpha / 2.
float geometrySmith(vec3 N, vec3 V, vec3 L, float roughness)
{
    float k = roughness * roughness / 2.0;
    float nv = max(dot(N, V), 0.0), nl = max(dot(N, L), 0.0);
    float gv = nv / (nv * (1.0 - k) + k);
    float gl = nl / (nl * (1.0 - k) + k);
    return gv * gl;
}
