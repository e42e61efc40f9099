// correct: theta from tan^2(theta) = alpha^2 Xi.y / (1 - Xi.y) (the same CDF, inverted for the
// tangent), tangents from cross(N, up) (the frame mirrored), another epsilon
vec3 importanceSampleGGX(vec2 Xi, vec3 N, float roughness)
{
    float alpha = roughness * roughness;
    float phi = 2.0 * PI * Xi.x;
    float theta = atan(alpha * sqrt(Xi.y / max(1.0 - Xi.y, 1e-6)));
    vec3 h = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));

    vec3 up = abs(N.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 T = normalize(cross(N, up));
    vec3 B = cross(N, T);
    return normalize(T * h.x + B * h.y + N * h.z);
}
