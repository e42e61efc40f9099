// Names every pbrlab program sees; part of the student contract (see DESIGN.md).
// Internal helpers start with pbrlab_ so a student's own helpers cannot collide with them.

const float PI = 3.14159265358979;

#ifndef NUM_LIGHTS
#define NUM_LIGHTS 1
#endif
// The arrays hold more slots than NUM_LIGHTS (the renderer sets PBRLAB_LIGHT_SLOTS), those past
// it black lights at the last light's position: GLSL leaves a read past an array's end
// undefined (Mesa reads zeros, WebGL reads the last element), and a loop with a hard-coded
// count reads there, so it reads the same on every GPU and its grade does not depend on one.
#ifndef PBRLAB_LIGHT_SLOTS
#define PBRLAB_LIGHT_SLOTS NUM_LIGHTS
#endif
uniform vec3 uLightPositions[PBRLAB_LIGHT_SLOTS];
uniform vec3 uLightColors[PBRLAB_LIGHT_SLOTS];

#ifdef PBRLAB_IBL
// Image-based lighting inputs (contract names), declared only in programs that use them.
uniform samplerCube uEnvironment;     // radiance, with mips
uniform samplerCube uIrradianceMap;   // stores E/PI
uniform samplerCube uPrefilterMap;    // roughness r at LOD r * uPrefilterMaxLod
uniform float uPrefilterMaxLod;
uniform sampler2D uBrdfLut;           // x = N.V, y = roughness; R = scale A, G = bias B
#endif

// normalize(v), or `fallback` when v is too short to have a direction (avoids 0/0 = NaN).
vec3 pbrlab_safeNormalize(vec3 v, vec3 fallback)
{
    float len2 = dot(v, v);
    return len2 < 1e-12 ? fallback : v * inversesqrt(len2);
}

// 0 over the grazing band 4 N.V N.L < 0.05, 1 above 0.1: views of the specular terms fade it
// out, because there the result depends only on each solution's own epsilon (see the
// specular and brdf handouts). Mirrored by pbrlab::grazingBand on the CPU.
float pbrlab_grazingBand(vec3 N, vec3 V, vec3 L)
{
    return smoothstep(0.05, 0.1, 4.0 * max(dot(N, V), 0.0) * max(dot(N, L), 0.0));
}
