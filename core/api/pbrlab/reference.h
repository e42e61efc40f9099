// The CPU truth: every contract function of the direct lab in double precision, with the same
// guards as the GLSL reference solutions (labs/<id>/solution.glsl), so GPU and CPU differ
// only by float rounding. Modules compose their CPU references from these.
#pragma once

#include <glm/glm.hpp>

namespace pbrlab::ref {

using glm::dvec2;
using glm::dvec3;
using glm::dvec4;

constexpr double kPi = 3.14159265358979323846;

// Guards shared with the GLSL solutions (documented in the handouts).
constexpr double kMinAlpha2 = 1e-7;           // GGX alpha^2 floor: roughness 0 stays finite
constexpr double kMinDistance2 = 1e-4;        // point light: 1/d^2 capped at d = 1 cm
constexpr double kSpecularDenomFloor = 1e-4;  // max(4 N.V N.L, floor)
constexpr double kLessonDenomEpsilon = 1e-3;  // the lesson's 4 N.V N.L + epsilon
constexpr double kAmbient = 0.03;             // reflectance: ambient = 0.03 * albedo * ao

struct PointLight {
    dvec3 position;
    dvec3 color;
};

// normalize(v), or `fallback` when |v|^2 is below 1e-12 (no direction to speak of).
dvec3 safeNormalize(const dvec3& v, const dvec3& fallback);

dvec3 srgbToLinear(const dvec3& c);  // 1 albedo
dvec3 pointLightRadiance(const dvec3& lightColor, const dvec3& lightPos,
                         const dvec3& worldPos);                           // 2 radiance
dvec3 halfwayVector(const dvec3& L, const dvec3& V);                       // 3 halfway
double lambertCosine(const dvec3& N, const dvec3& L);                      // 4 ndotl
double distributionGGX(const dvec3& N, const dvec3& H, double roughness);  // 5 ndf
double geometrySchlickGGX(double NdotX, double roughness);                 // 6 g1
double geometrySmith(const dvec3& N, const dvec3& V, const dvec3& L,
                     double roughness);                        // 7 smith
dvec3 baseReflectivity(const dvec3& albedo, double metallic);  // 8 f0
dvec3 fresnelSchlick(double cosTheta, const dvec3& F0);        // 9 fresnel
// How the specular denominator 4 N.V N.L is kept from zero: the reference's floor
// max(4 N.V N.L, 1e-4), or the lesson's (seed 001) 4 N.V N.L + 0.001. Both are correct; the
// pass bands of steps 10-12 span the two.
enum class DenominatorGuard { Floor, LessonEpsilon };
dvec3 cookTorranceSpecular(const dvec3& N, const dvec3& V, const dvec3& L, const dvec3& F0,
                           double roughness,
                           DenominatorGuard guard = DenominatorGuard::Floor);  // 10 specular
dvec3 cookTorranceBRDF(const dvec3& N, const dvec3& V, const dvec3& L, const dvec3& albedo,
                       double metallic, double roughness,
                       DenominatorGuard guard = DenominatorGuard::Floor);  // 11 brdf
dvec3 reflectedRadiance(const dvec3& P, const dvec3& N, const dvec3& V, const dvec3& albedo,
                        double metallic, double roughness, double ao, const PointLight* lights,
                        int lightCount,
                        DenominatorGuard guard = DenominatorGuard::Floor);         // 12 reflectance
dvec3 displayEncode(const dvec3& hdr);                                             // 13 tonemap
dvec3 normalFromMap(const dvec3& N, const dvec4& tangent, const dvec3& mapTexel);  // 14 normalmap

}  // namespace pbrlab::ref
