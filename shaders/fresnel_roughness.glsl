// Contract helper introduced by step `split_sum`, callable from that step on (contract.h,
// contractHelpers; an earlier step's program does not hold it): Schlick's Fresnel for
// ambient light. Light from the environment arrives over a whole lobe of half vectors, so the
// grazing-angle rise is capped for rough surfaces: the ceiling is max(1 - roughness, F0)
// instead of 1 (Lagarde's "fresnelSchlickRoughness"). cosTheta is N.V here.
vec3 fresnelSchlickRoughness(float cosTheta, vec3 F0, float roughness)
{
    return F0 + (max(vec3(1.0 - roughness), F0) - F0) *
                    pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}
