// expect: fits the reference with G1(N.V) for the light too
// mistake: copy-paste slip, G1 of N.V used twice (N.L never enters)
float geometrySmith(vec3 N, vec3 V, vec3 L, float roughness)
{
    float NdotV = max(dot(N, V), 0.0);
    float NdotL = max(dot(N, L), 0.0);
    return geometrySchlickGGX(NdotV, roughness) * geometrySchlickGGX(NdotV, roughness);
}
