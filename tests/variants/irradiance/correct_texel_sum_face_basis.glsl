// correct: texel sum over the mip whose faces are 64 wide, each face walked with its own basis
// (the face's axis and two tangents, as the cube map's texel layout lays them), the solid
// angle dA cos / r^2 of a texel at distance r on the unit cube, the cosine clamped by max()
const vec3 kAxis[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0),
                              vec3(0, 0, 1), vec3(0, 0, -1));
const vec3 kRight[6] = vec3[6](vec3(0, 0, -1), vec3(0, 0, 1), vec3(1, 0, 0), vec3(1, 0, 0),
                               vec3(1, 0, 0), vec3(-1, 0, 0));
const vec3 kDown[6] = vec3[6](vec3(0, -1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1),
                              vec3(0, -1, 0), vec3(0, -1, 0));

vec3 irradianceAt(vec3 N)
{
    int levels = findMSB(textureSize(uEnvironment, 0).x) + 1;
    int lod = max(levels - 7, 0);  // 64 texels a side, or the base when it is smaller
    int n = textureSize(uEnvironment, lod).x;
    float texel = 2.0 / float(n);
    vec3 total = vec3(0.0);
    for (int f = 0; f < 6; ++f) {
        for (int y = 0; y < n; ++y) {
            for (int x = 0; x < n; ++x) {
                vec3 p = kAxis[f] + kRight[f] * ((float(x) + 0.5) * texel - 1.0) +
                         kDown[f] * ((float(y) + 0.5) * texel - 1.0);
                float r2 = dot(p, p);
                float cosine = max(dot(N, p), 0.0) / sqrt(r2);
                float solidAngle = texel * texel / (r2 * sqrt(r2));
                total += textureLod(uEnvironment, p, float(lod)).rgb * cosine * solidAngle;
            }
        }
    }
    return total / PI;
}
