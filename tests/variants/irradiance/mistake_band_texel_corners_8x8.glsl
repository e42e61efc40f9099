// mistake: the texel sum over an 8 x 8 mip per face with each texel's direction taken at its
// corner (-1 + i h) instead of its centre (-1 + (i + 0.5) h): every direction is half a texel
// (7 degrees) off. Either change alone stays within the band (measured: the 8 x 8 mip with
// centres passes, corners on the 32 x 32 mip fail by 1.3 x the tolerance only).
// Fails by the value band alone (test_variants.cpp, mistake_band_*): irradiance has no sample
// count (no fall, bias or count checks), its overall factor stays within 3% and it is linear in
// radiance.
// expect: outside the band
vec3 irradianceAt(vec3 N)
{
    // An 8 x 8 mip per face.
    int baseSize = textureSize(uEnvironment, 0).x;
    int lod = max(findMSB(baseSize) - 3, 0);
    int size = max(baseSize >> lod, 1);
    float h = 2.0 / float(size);
    vec3 sum = vec3(0.0);
    for (int face = 0; face < 6; ++face) {
        for (int j = 0; j < size; ++j) {
            for (int i = 0; i < size; ++i) {
                float s = -1.0 + float(i) * h;  // the texel's corner, not its centre
                float t = -1.0 + float(j) * h;
                // The texel's direction (OpenGL cube map faces +X -X +Y -Y +Z -Z).
                vec3 d;
                if (face == 0) d = vec3(1.0, -t, -s);
                else if (face == 1) d = vec3(-1.0, -t, s);
                else if (face == 2) d = vec3(s, 1.0, t);
                else if (face == 3) d = vec3(s, -1.0, -t);
                else if (face == 4) d = vec3(s, -t, 1.0);
                else d = vec3(-s, -t, -1.0);
                float r2 = dot(d, d);  // 1 + s^2 + t^2
                float cosine = dot(N, d) * inversesqrt(r2);
                if (cosine > 0.0) {  // only light from the hemisphere above the surface
                    float solidAngle = h * h / (r2 * sqrt(r2));
                    sum += textureLod(uEnvironment, d, float(lod)).rgb * (cosine * solidAngle);
                }
            }
        }
    }
    return sum / PI;
}
