// correct: texel sum over a 32 x 32 mip per face with each texel's exact solid angle (from the
// solid angle of a rectangle on a cube face, atan(s t / sqrt(s^2 + t^2 + 1))), the cosine
// from normalize()
float texelCornerAngle(float s, float t)
{
    return atan(s * t, sqrt(s * s + t * t + 1.0));
}

vec3 irradianceAt(vec3 N)
{
    int base = textureSize(uEnvironment, 0).x;
    int lod = max(findMSB(base) - 5, 0);
    int size = max(base >> lod, 1);
    float h = 2.0 / float(size);
    vec3 E = vec3(0.0);
    for (int face = 0; face < 6; ++face)
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) {
                float s0 = -1.0 + float(i) * h, t0 = -1.0 + float(j) * h;
                float s = s0 + 0.5 * h, t = t0 + 0.5 * h;
                vec3 d = face == 0 ? vec3(1.0, -t, -s)
                       : face == 1 ? vec3(-1.0, -t, s)
                       : face == 2 ? vec3(s, 1.0, t)
                       : face == 3 ? vec3(s, -1.0, -t)
                       : face == 4 ? vec3(s, -t, 1.0)
                                   : vec3(-s, -t, -1.0);
                float c = max(dot(N, normalize(d)), 0.0);
                float omega = texelCornerAngle(s0 + h, t0 + h) - texelCornerAngle(s0, t0 + h) -
                              texelCornerAngle(s0 + h, t0) + texelCornerAngle(s0, t0);
                E += textureLod(uEnvironment, d, float(lod)).rgb * c * omega;
            }
    return E / PI;
}
