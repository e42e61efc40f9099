// correct: the unpacked map normal is normalised first, handedness multiplied by w
vec3 normalFromMap(vec3 N, vec4 tangent, vec3 mapTexel)
{
    vec3 n = normalize(2.0 * mapTexel - vec3(1.0));
    vec3 T = tangent.xyz - N * dot(N, tangent.xyz);
    T = T / length(T);
    vec3 B = tangent.w * cross(N, T);
    return normalize(n.x * T + n.y * B + n.z * N);
}
