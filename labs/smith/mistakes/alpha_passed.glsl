// expect: roughness^2 in place of roughness
// mistake: passes alpha = roughness^2 where G1 expects perceptual roughness
float geometrySmith(vec3 N, vec3 V, vec3 L, float roughness)
{
    float a = roughness * roughness;
    return geometrySchlickGGX(max(dot(N, V), 0.0), a) *
           geometrySchlickGGX(max(dot(N, L), 0.0), a);
}
