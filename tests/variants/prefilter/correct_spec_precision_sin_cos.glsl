// correct: the lesson's estimator on a GPU whose sin and cos are as inexact as the GLSL and
// Vulkan specifications allow (absolute error up to 2^-11 = 4.88e-4 on [-pi, pi]): its own
// GGX sampling, with sin and cos off by up to 4.8e-4. Such built-ins move every sample
// direction by up to ~5e-4 rad; next to the sky's sun the picture then differs from the same
// samples' CPU reference by up to 141x its band on 9% of the sphere grid's points (the
// quality line, not graded), and the graded checks, against the converged integral, pass.
// The page's prefilter on SwiftShader is off by the same order (100x on 1% of its view).
float specSin(float x)
{
    return sin(x) + 4.8e-4 * sin(37.0 * x);
}

float specCos(float x)
{
    return cos(x) + 4.8e-4 * cos(41.0 * x);
}

vec3 sampleGgxSpecBuiltins(vec2 Xi, vec3 N, float roughness)
{
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
    vec3 H = T * (sinTheta * specCos(phi)) + B * (sinTheta * specSin(phi)) + N * cosTheta;
    return normalize(H);
}

vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)
{
    vec3 N = R;
    vec3 V = R;
    uint n = max(sampleCount, 1u);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < n; ++i) {
        vec3 H = sampleGgxSpecBuiltins(hammersley(i, n), N, roughness);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            sum += textureLod(uEnvironment, L, 0.0).rgb * NdotL;
            weight += NdotL;
        }
    }
    // weight >= 1 as soon as sample 0 (H = N, N.L = 1) is used; the fallback keeps 0/0 out.
    return weight > 0.0 ? sum / weight : textureLod(uEnvironment, R, 0.0).rgb;
}
