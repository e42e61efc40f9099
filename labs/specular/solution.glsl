// Cook-Torrance specular lobe: facets oriented along H (D), not shadowed or masked (G),
// reflecting the Fresnel fraction of light at the angle between H and V (F), divided by
// 4 (N.V)(N.L) from the change of variables between facet normals and directions.
vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)
{
    // BEGIN SOLUTION
    vec3 H = halfwayVector(L, V);
    float D = distributionGGX(N, H, roughness);
    float G = geometrySmith(N, V, L, roughness);
    vec3 F = fresnelSchlick(max(dot(H, V), 0.0), F0);
    float denom = 4.0 * max(dot(N, V), 0.0) * max(dot(N, L), 0.0);
    return D * G * F / max(denom, 1e-4);
    // END SOLUTION
}
