// Precompute, the baseline of `pbrlab precompute --bench`: irradiance as LearnOpenGL's
// "Diffuse irradiance" chapter computes it, a Riemann sum over the hemisphere in spherical
// coordinates with one step uStep in theta and phi (their sampleDelta, 0.025 rad), starting
// at 0, each sample read with texture() so that the GPU picks the mip from the derivatives
// between neighbouring texels. Normalised as theirs: pi times the mean of L cos sin, which is
// E / pi (the E / pi the irradiance map holds).
#include "ibl/cube_face.glsl"

uniform int uFace;
uniform float uSize;
uniform float uStep;
layout(location = 0) out vec4 outColor;

void main()
{
    vec3 N = pbrlab_cubeDirection(uFace, gl_FragCoord.xy, uSize);
    vec3 T = normalize(cross(vec3(0.0, 1.0, 0.0), N));
    vec3 B = cross(N, T);
    vec3 sum = vec3(0.0);
    float count = 0.0;
    for (float phi = 0.0; phi < 2.0 * PI; phi += uStep) {
        for (float theta = 0.0; theta < 0.5 * PI; theta += uStep) {
            vec3 l = sin(theta) * (cos(phi) * T + sin(phi) * B) + cos(theta) * N;
            sum += texture(uEnvironment, l).rgb * (cos(theta) * sin(theta));
            count += 1.0;
        }
    }
    outColor = vec4(PI * sum / count, 1.0);
}
