// converge: the diffuse ambient term from 9 spherical-harmonic coefficients of the radiance
// (real SH, index l(l+1)+m), convolved with the clamped cosine: band l scaled by A_l / PI
// with A_0 = PI, A_1 = 2 PI / 3, A_2 = PI / 4 (so the result is E/PI).
uniform vec3 uSH[9];

vec3 view(Surface s)
{
    vec3 n = s.normal;
    float basis[9] = float[9](0.282095, 0.488603 * n.y, 0.488603 * n.z, 0.488603 * n.x,
                              1.092548 * n.x * n.y, 1.092548 * n.y * n.z,
                              0.315392 * (3.0 * n.z * n.z - 1.0), 1.092548 * n.x * n.z,
                              0.546274 * (n.x * n.x - n.y * n.y));
    const float band[9] = float[9](1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25);
    vec3 e = vec3(0.0);
    for (int i = 0; i < 9; ++i) e += uSH[i] * (band[i] * basis[i]);
    return s.albedo * max(e, 0.0);
}
