// What this step shows: where your half vectors go, through what does not depend on the tangent
// frame you chose around N (any orthonormal frame is correct):
//   red:   N.H of the sample for Xi, i.e. cos(theta_h), set by Xi.y alone. With Xi = uv on
//          the sphere grid, each sphere runs from N.H = 1 at the top (Xi.y = 0) to its lowest
//          at the bottom (Xi.y -> 1): smooth spheres stay bright almost to the bottom, rough
//          ones fade early.
//   green: |H|: 1 for the unit vector the contract asks for.
//   blue:  how phi turns: the dot product of the sideways parts (perpendicular to N) of the
//          samples for Xi and for Xi.x + 0.236068 (sqrt(5) - 2, wrapped into [0, 1)): with
//          phi = 2 pi Xi.x it is sin^2(theta) cos(2 pi 0.236068) in every frame.
//   scene: Xi = uv, with Xi.y stopped at 1 - 2^-12 (the largest value 4096 Hammersley points
//          reach; Xi.y = 1, at the south pole, is an extreme input);
//   probe, random inputs and stability sweep (their points carry inputs in extra): Xi =
//          extra.xy, clamped to the unit square (Xi.y = 1 does reach your function there).
vec3 view(Surface s)
{
    vec2 xi = any(notEqual(s.extra, vec4(0.0))) ? clamp(s.extra.xy, 0.0, 1.0)
                                                : vec2(s.uv.x, min(s.uv.y, 0.999755859375));
    vec3 N = s.normal;
    vec3 H = importanceSampleGGX(xi, N, s.roughness);
    vec3 H2 = importanceSampleGGX(vec2(fract(xi.x + 0.236068), xi.y), N, s.roughness);
    vec3 t1 = H - N * dot(N, H);
    vec3 t2 = H2 - N * dot(N, H2);
    return vec3(dot(N, H), length(H), dot(t1, t2));
}
