// Precompute (step.json "precompute", kind cube_mips): one mip of the prefiltered environment
// with this step's prefilterEnvironment, from the source cube bound as uEnvironment, at the
// mip's roughness uRoughness.
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
