// Precompute, a method of the host's (IblSettings::prefilter = Filtered): one mip of the
// prefiltered environment by filtered importance sampling (Krivanek and Colbert, GPU Gems 3,
// ch. 20), from the source cube bound as uEnvironment. Each sample reads the source mip whose
// texel covers about the solid angle the sample stands for, 1 / (n pdf), plus uLodBias mips,
// so a small bright sun is averaged instead of hit or missed (no fireflies on rough surfaces at
// modest sample counts). The bias is chosen by measured error (docs/ibl.md). Linked with the
// reference solutions of the step that provides uPrefilterMap (its samplers and D).
#include "ibl/cube_face.glsl"

uniform int uFace;
uniform float uSize;
uniform float uRoughness;
uniform uint uSampleCount;
uniform float uLodBias;
layout(location = 0) out vec4 outColor;

vec3 pbrlab_prefilterFiltered(vec3 R, float roughness, uint sampleCount)
{
    vec3 N = R, V = R;
    uint n = max(sampleCount, 1u);
    float sourceSize = float(textureSize(uEnvironment, 0).x);
    float texelSolidAngle = 4.0 * PI / (6.0 * sourceSize * sourceSize);
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (uint i = 0u; i < n; ++i) {
        vec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        vec3 L = 2.0 * dot(V, H) * H - V;
        float NdotL = dot(N, L);
        if (NdotL > 0.0) {
            // With N = V the pdf of L is D (N.H) / (4 V.H) = D / 4.
            float pdf = max(distributionGGX(N, H, roughness) * 0.25, 1e-8);
            float sampleSolidAngle = 1.0 / (float(n) * pdf);
            float lod = max(0.5 * log2(sampleSolidAngle / texelSolidAngle) + uLodBias, 0.0);
            sum += textureLod(uEnvironment, L, lod).rgb * NdotL;
            weight += NdotL;
        }
    }
    return weight > 0.0 ? sum / weight : textureLod(uEnvironment, R, 0.0).rgb;
}

void main()
{
    vec3 R = pbrlab_cubeDirection(uFace, gl_FragCoord.xy, uSize);
    outColor = vec4(pbrlab_prefilterFiltered(R, uRoughness, uSampleCount), 1.0);
}
