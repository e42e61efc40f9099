// What this step shows: how evenly the n points of your set cover the unit square. Each pixel
// stands for a box [0, a) x [0, b) with its corner (a, b) at the pixel and counts how many of
// the n points fall inside it, minus how many an exactly even spread would put there (n a b):
// the local discrepancy, in points (red). A low-discrepancy set keeps it within a few points
// everywhere, so the picture stays grey; clumps and gaps show as pink and teal patches. Green
// is n x_i - i for the point i whose column holds a: 0 when x_i = i / n.
//   scene: n = samples; the visible half of the sphere carries the square, a from the left
//          limb (0) to the right limb (1) along the longitude, b from the south pole (0) to
//          the north pole (1) along the latitude;
//   probe and stability sweep (their pixels carry inputs in extra): extra.x = a, the square
//          box [0, a) x [0, a); extra.y = n (1 to 1024: a set of 0 points has no point i).

vec3 view(Surface s)
{
    vec2 corner;
    uint n;
    if (any(notEqual(s.extra, vec4(0.0)))) {
        corner = vec2(clamp(s.extra.x, 0.0, 1.0));
        n = uint(clamp(s.extra.y, 1.0, 1024.0));
    } else {
        corner = vec2(abs(2.0 * s.uv.x - 1.0), 1.0 - s.uv.y);
        n = uint(clamp(u_samples, 1, 1024));
    }
    uint inside = 0u;
    for (uint j = 0u; j < n; ++j) {
        vec2 p = hammersley(j, n);
        if (p.x < corner.x && p.y < corner.y) ++inside;
    }
    float discrepancy = float(inside) - float(n) * corner.x * corner.y;
    uint slot = min(uint(corner.x * float(n)), n - 1u);
    float slotOffset = hammersley(slot, n).x * float(n) - float(slot);
    return vec3(discrepancy, slotOffset, 0.0);
}
