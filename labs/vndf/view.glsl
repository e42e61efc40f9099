// What this step shows: what every correct sampler has in common, whatever its frame and its
// mapping of Xi (Heitz's disk, spherical caps, ...): H is a unit vector (red: |1 - |H||),
// above the surface (green: how far N.H is below 0) and facing the viewer (blue: how far V.H
// is below 0; a visible microfacet faces V). A correct sampler draws black; its distribution
// is graded by a chi-square test (sample.glsl).
//   scene: Xi = uv, with Xi.x stopped at 1 - 2^-12 (the largest value 4096 Hammersley points
//          reach); probe, random inputs and stability sweep: Xi = extra.xy.
vec3 view(Surface s)
{
    vec2 xi = any(notEqual(s.extra, vec4(0.0))) ? s.extra.xy
                                                : vec2(min(s.uv.x, 0.999755859375), s.uv.y);
    vec3 H = importanceSampleVNDF(xi, s.normal, s.view, s.roughness);
    return vec3(abs(1.0 - length(H)), max(-dot(s.normal, H), 0.0), max(-dot(s.view, H), 0.0));
}
