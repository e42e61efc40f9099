// expect: without the [0,1] -> [-1,1] remap
// mistake: texel used as the normal without the [0,1] -> [-1,1] remap
vec3 normalFromMap(vec3 N, vec4 tangent, vec3 mapTexel)
{
    vec3 n = mapTexel;
    vec3 T = normalize(tangent.xyz - N * dot(N, tangent.xyz));
    vec3 B = cross(N, T) * tangent.w;
    return normalize(T * n.x + B * n.y + N * n.z);
}
