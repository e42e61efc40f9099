// expect: -tangent.w in place of tangent.w
// mistake: B = T x N instead of N x T (bitangent always points the wrong way)
vec3 normalFromMap(vec3 N, vec4 tangent, vec3 mapTexel)
{
    vec3 n = mapTexel * 2.0 - 1.0;
    vec3 T = normalize(tangent.xyz - N * dot(N, tangent.xyz));
    vec3 B = cross(T, N) * tangent.w;
    return normalize(T * n.x + B * n.y + N * n.z);
}
