// The display mapping of core/render/display.cpp (displayColor) on the GPU, for the GUI's live
// view: a value texture in, what a person sees out, no read-back. Output row 0 = the top of
// the picture (the value texture's last GL row), as images read back on the CPU are.
uniform sampler2D uValue;
uniform int uMode;  // DisplayMode, in declaration order
uniform float uLo, uHi;
uniform bool uLogScale;
uniform int uComponents;
layout(location = 0) out vec4 outColor;

const vec3 kBackground = vec3(0.12);

vec3 pbrlab_falseColor(float t)
{
    const vec3 stops[5] = vec3[5](vec3(0.02, 0.02, 0.12), vec3(0.30, 0.05, 0.55),
                                  vec3(0.80, 0.20, 0.35), vec3(0.98, 0.60, 0.10),
                                  vec3(1.00, 1.00, 0.75));
    if (!(t > 0.0)) t = 0.0;
    t = min(t, 1.0) * 4.0;
    int i = min(int(t), 3);
    return mix(stops[i], stops[i + 1], t - float(i));
}

float pbrlab_normalised(float v)
{
    if (uLogScale) return (log(max(v, 1e-30)) - log(uLo)) / (log(uHi) - log(uLo));
    return (v - uLo) / (uHi - uLo);
}

void main()
{
    ivec2 size = textureSize(uValue, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 value = texelFetch(uValue, ivec2(p.x, size.y - 1 - p.y), 0);
    vec3 v = value.rgb;
    if (uComponents == 1) v = vec3(v.x);
    if (uComponents == 2) v.z = 0.0;
    vec3 c;
    if (value.a == 0.0) c = kBackground;
    else if (any(isnan(v))) c = vec3(1.0, 0.0, 1.0);
    else if (any(isinf(v))) c = vec3(0.0, 1.0, 1.0);
    else if (uMode == 0) c = clamp(vec3(pbrlab_normalised(v.x), pbrlab_normalised(v.y), pbrlab_normalised(v.z)), 0.0, 1.0);
    else if (uMode == 1) c = pbrlab_srgbEncode(v);
    else if (uMode == 2) c = pow(max(v, 0.0) / (max(v, 0.0) + 1.0), vec3(1.0 / 2.2));
    else if (uMode == 3) c = clamp(0.5 + 0.5 * v, 0.0, 1.0);
    else if (uMode == 4) c = pbrlab_falseColor(pbrlab_normalised(v.x));
    else c = clamp(v, 0.0, 1.0);
    outColor = vec4(c, 1.0);
}
