// Precompute: one face of the environment cube from an equirectangular image.
#include "ibl/cube_face.glsl"

uniform sampler2D uEquirect;
uniform int uFace;
uniform float uSize;
layout(location = 0) out vec4 outColor;

void main()
{
    vec3 d = pbrlab_cubeDirection(uFace, gl_FragCoord.xy, uSize);
    outColor = vec4(textureLod(uEquirect, pbrlab_equirectUv(d), 0.0).rgb, 1.0);
}
