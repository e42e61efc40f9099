// Entry point of every module view: evaluates the module's view(Surface) per pixel into a
// float target (alpha = 1 where a surface was evaluated; 0.5 for the environment drawn behind
// it, which is shown but never compared).
layout(location = 0) out vec4 outValue;

#ifdef PBRLAB_SKY
uniform mat4 uInverseViewProjection;
uniform vec2 uViewportSize;

vec3 pbrlab_skyRadiance()
{
    vec2 ndc = gl_FragCoord.xy / uViewportSize * 2.0 - 1.0;
    vec4 far = uInverseViewProjection * vec4(ndc, 1.0, 1.0);
    return textureLod(uEnvironment, normalize(far.xyz / far.w - uCameraPosition), 0.0).rgb;
}
#endif

void main()
{
    Surface s = loadSurface();
#ifdef PBRLAB_SKY
    if (!s.covered) {
        outValue = vec4(pbrlab_skyRadiance(), 0.5);
        return;
    }
#endif
#ifdef PBRLAB_TRACE_NONFINITE
    // The diagnosis build (core/shader/preprocess.h): which of the student's calls made the
    // first NaN or Inf, another that made one, and whether the value is finite with what they
    // made replaced, in place of the value.
    if (s.covered) {
        vec3 repaired = view(s);
        outValue = vec4(float(pbrlab_traceSite), float(pbrlab_traceOther),
                        pbrlab_finite(repaired) ? 1.0 : 0.0, 1.0);
#ifdef PBRLAB_LOOP_GUARD
        // A loop cut by the guard (core/shader/loop_guard.h): which one, as -K.
        if (pbrlab_loopCut) outValue.z = -float(pbrlab_loopCutSite);
#endif
        return;
    }
#endif
    outValue = s.covered ? vec4(view(s), 1.0) : vec4(0.0);
#ifdef PBRLAB_LOOP_GUARD
    // A loop of a student's file cut by the guard (core/shader/loop_guard.h): the value is not
    // the function's, and NaN says so wherever it is read.
    if (pbrlab_loopCut) outValue.rgb = vec3(intBitsToFloat(0x7fc00000));
#endif
}
