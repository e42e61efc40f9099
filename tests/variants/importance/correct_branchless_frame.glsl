// correct: the lesson's formula (unguarded) in another orthonormal frame around N: the
// branchless basis of Duff et al. (2017). The density of H does not depend on the frame.
vec3 importanceSampleGGX(vec2 Xi, vec3 N, float roughness)
{
    float a = roughness * roughness;
    float phi = 2.0 * PI * Xi.x;
    float cosTheta = sqrt((1.0 - Xi.y) / (1.0 + (a * a - 1.0) * Xi.y));
    float sinTheta = sqrt(1.0 - cosTheta * cosTheta);

    float s = N.z >= 0.0 ? 1.0 : -1.0;
    float p = -1.0 / (s + N.z);
    float q = N.x * N.y * p;
    vec3 T = vec3(1.0 + s * N.x * N.x * p, s * q, -s * N.x);
    vec3 B = vec3(q, s + N.y * N.y * p, -N.y);
    return normalize(T * (sinTheta * cos(phi)) + B * (sinTheta * sin(phi)) + N * cosTheta);
}
