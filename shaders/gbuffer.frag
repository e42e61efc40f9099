// G-buffer pass: writes every surface input a module may read (layout in shaders/surface.glsl).
// Material maps are compiled in only when the material has them and the module reads them
// (HAS_*_MAP defines), so nothing is sampled, or loaded, that the step does not use. Every map
// multiplies its factor, as in glTF.
#include "color.glsl"

in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;
in vec4 vTangent;

layout(location = 0) out vec4 outPosition;   // xyz, covered = 1
layout(location = 1) out vec4 outNormal;     // xyz, roughness
layout(location = 2) out vec4 outTangent;    // xyz, handedness
layout(location = 3) out vec4 outUvMetalAo;  // uv, metallic, ao
layout(location = 4) out vec4 outAlbedoTexel;  // rgb, emissive.r
layout(location = 5) out vec4 outAlbedo;       // rgb, emissive.g
layout(location = 6) out vec4 outNormalTexel;  // rgb, emissive.b

uniform vec3 uAlbedo;       // linear factor
uniform vec3 uAlbedoTexel;  // the factor sRGB-encoded, as a texture would store it
uniform float uMetallic;
uniform float uRoughness;
uniform float uAo;
uniform float uOcclusionStrength;
uniform float uNormalScale;
uniform vec3 uEmissive;  // linear factor

#ifdef HAS_ALBEDO_MAP
uniform sampler2D uAlbedoMap;
#endif
#ifdef HAS_METALLIC_ROUGHNESS_MAP
uniform sampler2D uMetallicRoughnessMap;  // G = roughness, B = metallic
#endif
#ifdef HAS_ROUGHNESS_MAP
uniform sampler2D uRoughnessMap;
#endif
#ifdef HAS_METALLIC_MAP
uniform sampler2D uMetallicMap;
#endif
#ifdef HAS_AO_MAP
uniform sampler2D uAoMap;
#endif
#ifdef HAS_NORMAL_MAP
uniform sampler2D uNormalMap;
#endif
#ifdef HAS_EMISSIVE_MAP
uniform sampler2D uEmissiveMap;
#endif

void main()
{
    vec3 albedoTexel = uAlbedoTexel;
    vec3 albedo = uAlbedo;
#ifdef HAS_ALBEDO_MAP
    albedoTexel = texture(uAlbedoMap, vUv).rgb;
    albedo = uAlbedo * pbrlab_srgbDecode(albedoTexel);
#endif
    float roughness = uRoughness;
    float metallic = uMetallic;
#ifdef HAS_METALLIC_ROUGHNESS_MAP
    vec2 metallicRoughness = texture(uMetallicRoughnessMap, vUv).bg;
    metallic *= metallicRoughness.x;
    roughness *= metallicRoughness.y;
#endif
#ifdef HAS_ROUGHNESS_MAP
    roughness *= texture(uRoughnessMap, vUv).r;
#endif
#ifdef HAS_METALLIC_MAP
    metallic *= texture(uMetallicMap, vUv).r;
#endif
    float ao = uAo;
#ifdef HAS_AO_MAP
    ao *= 1.0 + uOcclusionStrength * (texture(uAoMap, vUv).r - 1.0);
#endif
    vec3 normalTexel = vec3(0.5, 0.5, 1.0);
#ifdef HAS_NORMAL_MAP
    normalTexel = texture(uNormalMap, vUv).rgb;
    // glTF's normal scale stretches the tangent-space x and y; 1 keeps the texel as stored.
    normalTexel.xy = (normalTexel.xy * 2.0 - 1.0) * uNormalScale * 0.5 + 0.5;
#endif
    vec3 emissive = uEmissive;
#ifdef HAS_EMISSIVE_MAP
    emissive *= pbrlab_srgbDecode(texture(uEmissiveMap, vUv).rgb);
#endif
    outPosition = vec4(vPosition, 1.0);
    outNormal = vec4(normalize(vNormal), roughness);
    outTangent = vec4(normalize(vTangent.xyz), vTangent.w < 0.0 ? -1.0 : 1.0);
    outUvMetalAo = vec4(vUv, metallic, ao);
    outAlbedoTexel = vec4(albedoTexel, emissive.r);
    outAlbedo = vec4(albedo, emissive.g);
    outNormalTexel = vec4(normalTexel, emissive.b);
}
