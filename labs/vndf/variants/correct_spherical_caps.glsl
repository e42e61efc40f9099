// A correct variant: Dupuy and Benyoub 2023, "Sampling Visible GGX Normals with Spherical
// Caps": in the stretched configuration, the visible normals are the directions c + Vh with c
// uniform on the spherical cap z >= -Vh.z. Another mapping of Xi than Heitz's: the same
// distribution, other samples.
vec3 importanceSampleVNDF(vec2 Xi, vec3 N, vec3 V, float roughness)
{
    float a = max(roughness * roughness, 3.1622777e-4);
    vec3 up = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 T = normalize(cross(up, N));
    vec3 B = cross(N, T);
    vec3 Ve = vec3(dot(V, T), dot(V, B), max(dot(V, N), 1e-4));
    vec3 Vh = normalize(vec3(a * Ve.xy, Ve.z));
    float phi = 2.0 * PI * Xi.x;
    float z = (1.0 - Xi.y) * (1.0 + Vh.z) - Vh.z;
    float sinTheta = sqrt(clamp(1.0 - z * z, 0.0, 1.0));
    vec3 Hh = vec3(sinTheta * cos(phi), sinTheta * sin(phi), z) + Vh;
    vec3 He = normalize(vec3(a * Hh.xy, max(Hh.z, 0.0)));
    return normalize(T * He.x + B * He.y + N * He.z);
}
