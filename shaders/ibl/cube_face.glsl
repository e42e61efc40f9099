// The direction through the centre of texel `fragCoord` of cube face `face` (OpenGL's cube map
// convention: +X -X +Y -Y +Z -Z; texel row 0 has t = 0).
vec3 pbrlab_cubeDirection(int face, vec2 fragCoord, float size)
{
    vec2 st = fragCoord / size * 2.0 - 1.0;  // fragCoord is already at the texel centre
    float s = st.x, t = st.y;
    vec3 d;
    if (face == 0) d = vec3(1.0, -t, -s);
    else if (face == 1) d = vec3(-1.0, -t, s);
    else if (face == 2) d = vec3(s, 1.0, t);
    else if (face == 3) d = vec3(s, -1.0, -t);
    else if (face == 4) d = vec3(s, -t, 1.0);
    else d = vec3(-s, -t, -1.0);
    return normalize(d);
}

// Equirectangular lookup: u = 0.5 at -Z, around +Y; v = 0 at the zenith (image row 0).
vec2 pbrlab_equirectUv(vec3 d)
{
    return vec2(atan(d.x, -d.z) / (2.0 * PI) + 0.5, acos(clamp(d.y, -1.0, 1.0)) / PI);
}
