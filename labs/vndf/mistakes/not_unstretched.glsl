// expect: do not follow the distribution of visible normals
// mistake: the sample left in the stretched configuration: the hemisphere's normal Nh returned without scaling its x and y back by alpha
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
    float s = 0.5 * (1.0 + Vh.z);
    t2 = (1.0 - s) * sqrt(max(1.0 - t1 * t1, 0.0)) + s * t2;
    vec3 Nh = t1 * T1 + t2 * T2 + sqrt(max(0.0, 1.0 - t1 * t1 - t2 * t2)) * Vh;
    return normalize(T * Nh.x + B * Nh.y + N * Nh.z);
}
