// converge: the specular ambient term by the split sum: prefiltered radiance times the LUT.
vec3 view(Surface s)
{
    vec3 F0 = baseReflectivity(s.albedo, s.metallic);
    float NdotV = max(dot(s.normal, s.view), 0.0);
    vec3 prefiltered =
        textureLod(uPrefilterMap, reflect(-s.view, s.normal), s.roughness * uPrefilterMaxLod).rgb;
    vec2 AB = textureLod(uBrdfLut, vec2(NdotV, s.roughness), 0.0).rg;
    return prefiltered * (F0 * AB.x + AB.y);
}
