// What step 16 shows: where your half vectors go, through what does not depend on the tangent
// frame you chose around N (any orthonormal frame is correct):
//   red:   N.H of the sample for Xi, i.e. cos(theta_h). With Xi = uv on the sphere grid, each
//          sphere runs from N.H = 1 at the top (Xi.y = 0) to its lowest at the bottom
//          (Xi.y -> 1): smooth spheres stay bright almost to the bottom, rough ones fade early.
//   green: how lopsided the samples are around N: the 8 samples with the same Xi.y and
//          Xi.x spread evenly over [0, 1) are averaged; their sideways parts cancel when phi
//          turns once around N, so only the part along N is left. Green is the length of the
//          sideways part: 0 (black) when phi is right.
//   scene: Xi = uv, with Xi.y stopped at 1 - 2^-12 (the largest value 4096 Hammersley points
//          reach; Xi.y = 1, at the south pole, is an extreme input);
//   probe and stability sweep (their pixels carry inputs in extra): Xi = extra.xy, clamped to
//          the unit square (Xi.y = 1 does reach your function there).
vec3 view(Surface s)
{
    vec2 xi = any(notEqual(s.extra, vec4(0.0))) ? clamp(s.extra.xy, 0.0, 1.0)
                                                : vec2(s.uv.x, min(s.uv.y, 0.999755859375));
    vec3 N = s.normal;
    vec3 H = importanceSampleGGX(xi, N, s.roughness);
    vec3 ring = vec3(0.0);
    for (int k = 0; k < 8; ++k)
        ring += importanceSampleGGX(vec2((float(k) + xi.x) / 8.0, xi.y), N, s.roughness);
    ring /= 8.0;
    vec3 sideways = ring - N * dot(N, ring);
    return vec3(dot(N, H), length(sideways), 0.0);
}
