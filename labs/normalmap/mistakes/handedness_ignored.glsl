// expect: wrong only where tangent.w < 0
// mistake: tangent.w ignored, mirrored UVs get an inverted bitangent
vec3 normalFromMap(vec3 N, vec4 tangent, vec3 mapTexel)
{
    vec3 n = mapTexel * 2.0 - 1.0;
    vec3 T = normalize(tangent.xyz - N * dot(N, tangent.xyz));
    vec3 B = cross(N, T);
    return normalize(T * n.x + B * n.y + N * n.z);
}
