// Turns a module's value image into what a person sees. Modes follow pbrlab::DisplayMode.
// Non-finite values are painted so they cannot hide: NaN magenta, infinity cyan.
#include "color.glsl"

uniform sampler2D uValue;
uniform int uMode;
uniform float uLo;
uniform float uHi;
uniform bool uLogScale;
uniform int uComponents;

layout(location = 0) out vec4 outColor;

const vec3 kBackground = vec3(0.12);
const vec3 kNanColor = vec3(1.0, 0.0, 1.0);
const vec3 kInfColor = vec3(0.0, 1.0, 1.0);

// A colour map of our own: dark blue -> purple -> orange -> pale yellow, monotonic in
// lightness so that order reads correctly in grey too.
vec3 pbrlab_falseColor(float t)
{
    const vec3 stops[5] = vec3[5](vec3(0.02, 0.02, 0.12), vec3(0.30, 0.05, 0.55),
                                  vec3(0.80, 0.20, 0.35), vec3(0.98, 0.60, 0.10),
                                  vec3(1.00, 1.00, 0.75));
    t = clamp(t, 0.0, 1.0) * 4.0;
    int i = min(int(t), 3);
    return mix(stops[i], stops[i + 1], t - float(i));
}

float pbrlab_normalised(float v)
{
    if (uLogScale)
        return (log(max(v, 1e-30)) - log(uLo)) / (log(uHi) - log(uLo));
    return (v - uLo) / (uHi - uLo);
}

void main()
{
    vec4 value = texelFetch(uValue, ivec2(gl_FragCoord.xy), 0);
    vec3 v = value.rgb;
    if (uComponents == 1) v = vec3(v.r);
    if (uComponents == 2) v = vec3(v.rg, 0.0);
    vec3 c;
    if (value.a == 0.0) {
        c = kBackground;
    } else if (any(isnan(v))) {
        c = kNanColor;
    } else if (any(isinf(v))) {
        c = kInfColor;
    } else if (uMode == 0) {
        c = clamp(vec3(pbrlab_normalised(v.r), pbrlab_normalised(v.g), pbrlab_normalised(v.b)),
                  0.0, 1.0);
        if (uComponents == 1) c = vec3(c.r);
    } else if (uMode == 1) {
        c = pbrlab_srgbEncode(v);
    } else if (uMode == 2) {
        vec3 h = max(v, 0.0);
        c = pow(h / (h + 1.0), vec3(1.0 / 2.2));
    } else if (uMode == 3) {
        c = clamp(0.5 + 0.5 * v, 0.0, 1.0);
    } else if (uMode == 4) {
        c = pbrlab_falseColor(pbrlab_normalised(v.r));
    } else {
        c = clamp(v, 0.0, 1.0);
    }
    outColor = vec4(c, 1.0);
}
