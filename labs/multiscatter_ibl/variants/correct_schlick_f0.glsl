// A correct variant in the style of three.js's computeMultiscattering: Schlick's F0 in the
// single-scattering part (FssEss = F0 A + B, as split_sum's specular), the rest the paper's.
vec3 ambientIBLMultiscatter(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)
{
    float cosine = clamp(dot(N, V), 0.0, 1.0);
    vec3 specularColor = mix(vec3(0.04), albedo, metallic);
    vec2 fab = texture(uBrdfLut, vec2(cosine, roughness)).rg;
    vec3 singleScatter = specularColor * fab.x + fab.y;
    float totalScatter = fab.x + fab.y;
    float lost = 1.0 - totalScatter;
    vec3 averageFresnel = specularColor + (1.0 - specularColor) * 0.047619;
    vec3 multiScatter = lost * singleScatter * averageFresnel / (1.0 - lost * averageFresnel);
    vec3 diffuseColor = albedo * (1.0 - metallic);
    vec3 diffuse = diffuseColor * (1.0 - singleScatter - multiScatter);
    vec3 radiance = textureLod(uPrefilterMap, reflect(-V, N), roughness * uPrefilterMaxLod).rgb;
    vec3 irradiance = texture(uIrradianceMap, N).rgb;
    return ao * (singleScatter * radiance + (multiScatter + diffuse) * irradiance);
}
