// expect: facing V
// mistake: the whole disk sampled, without squeezing its far half by s = (1 + Vh.z) / 2: part of the samples are normals the view cannot see
vec3 importanceSampleVNDF(vec2 Xi, vec3 N, vec3 V, float roughness)
{
    float a = max(roughness * roughness, 3.1622777e-4);
    vec3 up = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 T = normalize(cross(up, N));
    vec3 B = cross(N, T);
    vec3 Ve = vec3(dot(V, T), dot(V, B), max(dot(V, N), 1e-4));
    vec3 Vh = normalize(vec3(a * Ve.x, a * Ve.y, Ve.z));
    float lensq = Vh.x * Vh.x + Vh.y * Vh.y;
    vec3 T1 = lensq > 0.0 ? vec3(-Vh.y, Vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
    vec3 T2 = cross(Vh, T1);
    float r = sqrt(Xi.x);
    float phi = 2.0 * PI * Xi.y;
    float t1 = r * cos(phi);
    float t2 = r * sin(phi);
    vec3 Nh = t1 * T1 + t2 * T2 + sqrt(max(0.0, 1.0 - t1 * t1 - t2 * t2)) * Vh;
    vec3 He = normalize(vec3(a * Nh.x, a * Nh.y, max(0.0, Nh.z)));
    return normalize(T * He.x + B * He.y + N * He.z);
}
