// The per-pixel inputs of a module's view, read from the G-buffer (scene) or from textures
// the host filled (probe, PBRLAB_PROBE defined). The CPU reference reads the same values:
// keep this in step with pbrlab::Surface and core/render/surface_io.cpp.

struct Surface {
    bool covered;        // false: background
    vec3 position;
    vec3 normal;
    vec4 tangent;        // xyz, w = handedness
    vec2 uv;
    vec3 view;           // V, towards the camera
    vec3 light;          // L, towards the first light (zero vector when on it)
    vec3 lightPosition;  // first light
    vec3 lightColor;
    vec3 albedoTexel;    // base colour as stored (sRGB-encoded)
    vec3 albedo;         // linear
    float metallic;
    float roughness;
    float ao;
    vec3 normalTexel;    // tangent-space normal map texel in [0, 1]
    vec3 emissive;       // emitted radiance, linear (what the final-picture views add)
    vec4 extra;          // probe-only inputs, meaning given by the module
};

uniform sampler2D uSurface0;
uniform sampler2D uSurface1;
uniform sampler2D uSurface2;
uniform sampler2D uSurface3;
uniform sampler2D uSurface4;
uniform sampler2D uSurface5;
uniform sampler2D uSurface6;
#ifdef PBRLAB_PROBE
uniform sampler2D uSurface7;
uniform sampler2D uSurface8;
uniform sampler2D uSurface9;
uniform sampler2D uSurface10;
uniform sampler2D uSurface11;
// The side of the quad each point is drawn as (RenderRequest::isolatePoints): a point's
// inputs are one texel, read by every pixel of its quad.
uniform int uPointQuad;
#else
uniform vec3 uCameraPosition;
#endif

Surface loadSurface()
{
#ifdef PBRLAB_PROBE
    ivec2 p = ivec2(gl_FragCoord.xy) / max(uPointQuad, 1);
#else
    ivec2 p = ivec2(gl_FragCoord.xy);
#endif
    vec4 t0 = texelFetch(uSurface0, p, 0);
    vec4 t1 = texelFetch(uSurface1, p, 0);
    vec4 t3 = texelFetch(uSurface3, p, 0);
    Surface s;
    s.covered = t0.w > 0.5;
    s.position = t0.xyz;
    s.normal = t1.xyz;
    s.roughness = t1.w;
    s.tangent = texelFetch(uSurface2, p, 0);
    s.uv = t3.xy;
    s.metallic = t3.z;
    s.ao = t3.w;
    vec4 t4 = texelFetch(uSurface4, p, 0);
    vec4 t5 = texelFetch(uSurface5, p, 0);
    vec4 t6 = texelFetch(uSurface6, p, 0);
    s.albedoTexel = t4.rgb;
    s.albedo = t5.rgb;
    s.normalTexel = t6.rgb;
    s.emissive = vec3(t4.a, t5.a, t6.a);
#ifdef PBRLAB_PROBE
    s.view = texelFetch(uSurface7, p, 0).xyz;
    s.light = texelFetch(uSurface8, p, 0).xyz;
    s.lightPosition = texelFetch(uSurface9, p, 0).xyz;
    s.lightColor = texelFetch(uSurface10, p, 0).rgb;
    s.extra = texelFetch(uSurface11, p, 0);
#else
    s.view = pbrlab_safeNormalize(uCameraPosition - s.position, vec3(0.0, 0.0, 1.0));
    s.lightPosition = uLightPositions[0];
    s.lightColor = uLightColors[0];
    s.light = pbrlab_safeNormalize(s.lightPosition - s.position, vec3(0.0));
    s.extra = vec4(0.0);
#endif
    return s;
}
