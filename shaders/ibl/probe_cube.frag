// Reads a cube map at given directions (one per texel of uDirections), as the renderer reads
// it: bilinear within the mip uLod, seamless across faces. The GPU side of the precompute's
// error measurement (core/ibl/map_error.cpp).
uniform sampler2D uDirections;
uniform samplerCube uMap;
uniform float uLod;
layout(location = 0) out vec4 outColor;

void main()
{
    vec3 d = texelFetch(uDirections, ivec2(gl_FragCoord.xy), 0).xyz;
    outColor = vec4(textureLod(uMap, d, uLod).rgb, 1.0);
}
