// correct: TBN built as a mat3 (Gram-Schmidt on the tangent, sign of w for handedness)
vec3 normalFromMap(vec3 N, vec4 tangent, vec3 mapTexel)
{
    vec3 T = normalize(tangent.xyz - dot(tangent.xyz, N) * N);
    vec3 B = cross(N, T) * sign(tangent.w);
    mat3 TBN = mat3(T, B, N);
    return normalize(TBN * (mapTexel * 2.0 - 1.0));
}
