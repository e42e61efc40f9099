// Smith's shadowing-masking: light must reach a facet (shadowing, along L) and leave it
// towards the eye (masking, along V). Treating both as independent, the visible fraction is
// the product of one Schlick-GGX term per direction.
float geometrySmith(vec3 N, vec3 V, vec3 L, float roughness)
{
    // BEGIN SOLUTION
    float NdotV = max(dot(N, V), 0.0);
    float NdotL = max(dot(N, L), 0.0);
    return geometrySchlickGGX(NdotV, roughness) * geometrySchlickGGX(NdotL, roughness);
    // END SOLUTION
}
