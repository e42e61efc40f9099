// correct: texel sum over the mip whose faces are 32 wide, skipping the faces that lie wholly
// below N's horizon (N.d is linear over a face, so a face whose four corners are at or below the
// horizon is too), the solid angle written (1 + s^2 + t^2)^(-3/2) h^2 and the direction
// normalised with inversesqrt
vec3 faceDirection(int face, float s, float t)
{
    if (face == 0) return vec3(1.0, -t, -s);
    if (face == 1) return vec3(-1.0, -t, s);
    if (face == 2) return vec3(s, 1.0, t);
    if (face == 3) return vec3(s, -1.0, -t);
    if (face == 4) return vec3(s, -t, 1.0);
    return vec3(-s, -t, -1.0);
}

vec3 irradianceAt(vec3 N)
{
    int size0 = textureSize(uEnvironment, 0).x;
    int lod = 0;
    while ((size0 >> lod) > 32) ++lod;
    int size = size0 >> lod;
    float h = 2.0 / float(size);
    vec3 E = vec3(0.0);
    for (int face = 0; face < 6; ++face) {
        bool visible = false;
        for (int c = 0; c < 4; ++c)
            visible = visible || dot(N, faceDirection(face, (c & 1) == 0 ? -1.0 : 1.0,
                                           (c & 2) == 0 ? -1.0 : 1.0)) > 0.0;
        if (!visible) continue;
        for (int j = 0; j < size; ++j) {
            float t = -1.0 + (float(j) + 0.5) * h;
            for (int i = 0; i < size; ++i) {
                float s = -1.0 + (float(i) + 0.5) * h;
                vec3 d = faceDirection(face, s, t);
                float q = 1.0 + s * s + t * t;
                float cosine = dot(N, d) * inversesqrt(q);
                if (cosine <= 0.0) continue;
                E += textureLod(uEnvironment, d, float(lod)).rgb * cosine * h * h *
                     inversesqrt(q * q * q);
            }
        }
    }
    return E * (1.0 / PI);
}
