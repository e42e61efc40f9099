// Ambient light from the environment in real time (the split sum): three precomputed lookups
// replace the integrals.
//   diffuse:  albedo * irradiance, with uIrradianceMap storing E / PI at N;
//   specular: prefiltered * (F0 * A + B), the prefiltered environment at R = reflect(-V, N)
//             read at LOD roughness * uPrefilterMaxLod, and the BRDF LUT at
//             (N.V, roughness) giving scale A (red) and bias B (green). F0, not F: the
//             Fresnel term is already inside A and B (Karis 2013).
// kD = (1 - F)(1 - metallic) with F = fresnelSchlickRoughness(N.V, F0, roughness): light
// reflected specularly does not enter the diffuse layer, and metals have none.
vec3 ambientIBL(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    // BEGIN SOLUTION
    // max(N.V, 0): V below the horizon (interpolated normals at silhouettes) reads the LUT and
    // Fresnel at grazing incidence.
    float NdotV = max(dot(N, V), 0.0);
    vec3 R = reflect(-V, N);
    vec3 F0 = baseReflectivity(albedo, metallic);
    vec3 F = fresnelSchlickRoughness(NdotV, F0, roughness);
    vec3 kD = (1.0 - F) * (1.0 - metallic);
    vec3 diffuse = albedo * textureLod(uIrradianceMap, N, 0.0).rgb;
    vec3 prefiltered = textureLod(uPrefilterMap, R, roughness * uPrefilterMaxLod).rgb;
    vec2 AB = textureLod(uBrdfLut, vec2(NdotV, roughness), 0.0).rg;
    vec3 specular = prefiltered * (F0 * AB.x + AB.y);
    return (kD * diffuse + specular) * ao;
    // END SOLUTION
}
