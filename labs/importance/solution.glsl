// GGX importance sampling: turns a uniform point Xi of the unit square into a half vector H
// around N distributed like the microfacet normals, with density D(H) (N.H) per steradian.
// Inverting the cumulative distribution of that density in theta gives
//     phi = 2 pi Xi.x,   cos^2(theta) = (1 - Xi.y) / (1 + (alpha^2 - 1) Xi.y),
// with alpha = roughness^2. The sample is built in a tangent frame (T, B, N) and returned in
// world space.
vec3 importanceSampleGGX(vec2 Xi, vec3 N, float roughness)
{
    // BEGIN SOLUTION
    float a = roughness * roughness;
    // alpha^2 floored like distributionGGX: at roughness 0 the denominator below stays > 0.
    float a2 = max(a * a, 1e-7);
    vec2 u = clamp(Xi, 0.0, 1.0);
    float phi = 2.0 * PI * u.x;
    // The denominator regrouped as (1 - y) + alpha^2 y, and sin^2 = alpha^2 y / (same): sin(theta)
    // never comes from 1 - cos^2, which cancels to nothing in float for narrow lobes.
    float oneMinusY = 1.0 - u.y;
    float denom = oneMinusY + a2 * u.y;
    float cosTheta = sqrt(oneMinusY / denom);
    float sinTheta = sqrt(a2 * u.y / denom);
    // Tangent frame: up = z, unless N is within ~2.6 degrees of +-z (cross product too short).
    vec3 up = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 T = normalize(cross(up, N));
    vec3 B = cross(N, T);
    vec3 H = T * (sinTheta * cos(phi)) + B * (sinTheta * sin(phi)) + N * cosTheta;
    return normalize(H);
    // END SOLUTION
}
