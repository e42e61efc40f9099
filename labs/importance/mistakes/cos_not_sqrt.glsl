// expect: to the power 2 (x^2 where the reference has x): is a square root missing
// mistake: the square root is missing: cos(theta) set to what is cos^2(theta)
vec3 importanceSampleGGX(vec2 Xi, vec3 N, float roughness)
{
    float a = roughness * roughness;
    float phi = 2.0 * PI * Xi.x;
    float cosTheta = (1.0 - Xi.y) / (1.0 + (a * a - 1.0) * Xi.y);
    float sinTheta = sqrt(1.0 - cosTheta * cosTheta);
    vec3 up = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 T = normalize(cross(up, N));
    vec3 B = cross(N, T);
    return normalize(T * (sinTheta * cos(phi)) + B * (sinTheta * sin(phi)) + N * cosTheta);
}
