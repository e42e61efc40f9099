// Precompute (step.json "precompute", kind cube): the irradiance cube (stores E/PI) with this
// step's irradianceAt.
#include "ibl/cube_face.glsl"

uniform int uFace;
uniform float uSize;
layout(location = 0) out vec4 outColor;

void main()
{
    outColor = vec4(irradianceAt(pbrlab_cubeDirection(uFace, gl_FragCoord.xy, uSize)), 1.0);
}
