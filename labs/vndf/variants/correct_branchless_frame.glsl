// A correct variant: Heitz's sampler in the branchless orthonormal frame of Duff et al. 2017
// (no cone around +-z to switch at), with Xi's coordinates used the other way round (the
// radius from Xi.y, the angle from Xi.x): a mirror of the unit square, the same distribution.
vec3 importanceSampleVNDF(vec2 Xi, vec3 N, vec3 V, float roughness)
{
    float sign_ = N.z >= 0.0 ? 1.0 : -1.0;
    float p = -1.0 / (sign_ + N.z);
    float q = N.x * N.y * p;
    vec3 T = vec3(1.0 + sign_ * N.x * N.x * p, sign_ * q, -sign_ * N.x);
    vec3 B = vec3(q, sign_ + N.y * N.y * p, -N.y);
    float alpha = max(roughness * roughness, 3.1622777e-4);
    vec3 Vh = normalize(vec3(alpha * dot(V, T), alpha * dot(V, B), max(dot(V, N), 1e-4)));
    float lensq = dot(Vh.xy, Vh.xy);
    vec3 T1 = lensq > 0.0 ? vec3(-Vh.y, Vh.x, 0.0) / sqrt(lensq) : vec3(1.0, 0.0, 0.0);
    vec3 T2 = cross(Vh, T1);
    float r = sqrt(clamp(Xi.y, 0.0, 1.0));
    float angle = 2.0 * PI * Xi.x;
    float t1 = r * cos(angle);
    float s = 0.5 * (1.0 + Vh.z);
    float t2 = mix(sqrt(max(1.0 - t1 * t1, 0.0)), r * sin(angle), s);
    vec3 Nh = t1 * T1 + t2 * T2 + sqrt(max(0.0, 1.0 - t1 * t1 - t2 * t2)) * Vh;
    vec3 H = normalize(vec3(alpha * Nh.xy, max(Nh.z, 0.0)));
    return normalize(H.x * T + H.y * B + H.z * N);
}
