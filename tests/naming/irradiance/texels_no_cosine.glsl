// expect: no cosine N.L
// A texel sum over the hemisphere that forgets to weight by the cosine.
vec3 irradianceAt(vec3 N)
{
    int base = textureSize(uEnvironment, 0).x;
    int lod = max(findMSB(base) - 5, 0);
    int size = max(base >> lod, 1);
    float h = 2.0 / float(size);
    vec3 E = vec3(0.0);
    for (int face = 0; face < 6; ++face) {
        for (int j = 0; j < size; ++j) {
            for (int i = 0; i < size; ++i) {
                vec2 st = vec2(-1.0) + (vec2(i, j) + 0.5) * h;
                vec3 dir;
                if (face == 0) dir = vec3(1.0, -st.y, -st.x);
                else if (face == 1) dir = vec3(-1.0, -st.y, st.x);
                else if (face == 2) dir = vec3(st.x, 1.0, st.y);
                else if (face == 3) dir = vec3(st.x, -1.0, -st.y);
                else if (face == 4) dir = vec3(st.x, -st.y, 1.0);
                else dir = vec3(-st.x, -st.y, -1.0);
                float len2 = dot(dir, dir);
                if (dot(N, dir) > 0.0)
                    E += textureLod(uEnvironment, dir, float(lod)).rgb * h * h /
                         (len2 * sqrt(len2));
            }
        }
    }
    return E / PI;
}
