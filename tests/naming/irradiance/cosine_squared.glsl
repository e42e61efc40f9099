// expect: (N.L)^2
// A texel sum whose weight has the cosine twice (once for the texel's tilt, once again).
vec3 irradianceAt(vec3 N)
{
    int size = 32;
    int lod = max(findMSB(textureSize(uEnvironment, 0).x) - 5, 0);
    float h = 2.0 / float(size);
    vec3 total = vec3(0.0);
    for (int face = 0; face < 6; ++face)
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) {
                float s = -1.0 + (float(i) + 0.5) * h, t = -1.0 + (float(j) + 0.5) * h;
                vec3 d = face == 0 ? vec3(1.0, -t, -s)
                       : face == 1 ? vec3(-1.0, -t, s)
                       : face == 2 ? vec3(s, 1.0, t)
                       : face == 3 ? vec3(s, -1.0, -t)
                       : face == 4 ? vec3(s, -t, 1.0)
                                   : vec3(-s, -t, -1.0);
                float r2 = dot(d, d);
                float c = dot(N, normalize(d));
                if (c > 0.0)
                    total += textureLod(uEnvironment, d, float(lod)).rgb * c * c * h * h /
                             (r2 * sqrt(r2));
            }
    return total / PI;
}
