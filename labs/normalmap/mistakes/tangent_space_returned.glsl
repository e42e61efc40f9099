// expect: does not change with the normal N, the tangent
// mistake: the tangent-space normal returned as if it were in world space (no TBN)
vec3 normalFromMap(vec3 N, vec4 tangent, vec3 mapTexel)
{
    return normalize(mapTexel * 2.0 - 1.0);
}
