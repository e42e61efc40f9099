// Precompute: one mip of the prefiltered environment with the step 19 function.
#include "ibl/cube_face.glsl"

uniform int uFace;
uniform float uSize;
uniform float uRoughness;
uniform uint uSampleCount;
layout(location = 0) out vec4 outColor;

void main()
{
    vec3 R = pbrlab_cubeDirection(uFace, gl_FragCoord.xy, uSize);
    outColor = vec4(prefilterEnvironment(R, uRoughness, uSampleCount), 1.0);
}
