// CPU references of the direct lab in double precision. Each function mirrors the GLSL
// reference solution of its step (labs/<id>/solution.glsl) formula for formula and guard for
// guard, so the two differ only by float rounding.
#include "pbrlab/reference.h"

#include <algorithm>
#include <cmath>

#include "util/color.h"

namespace pbrlab::ref {

namespace {

// Below this squared length a vector has no usable direction (same threshold as
// pbrlab_safeNormalize in shaders/common.glsl).
constexpr double kMinLength2 = 1e-12;
// Reflectance at normal incidence of a typical dielectric (metallic workflow).
constexpr double kDielectricF0 = 0.04;

// A unit vector perpendicular to N, deterministic: the coordinate axis least aligned with N
// (x unless N is close to x), projected onto the plane of N.
dvec3 perpendicularTo(const dvec3& N) {
    const dvec3 axis = std::abs(N.x) < 0.9 ? dvec3(1.0, 0.0, 0.0) : dvec3(0.0, 1.0, 0.0);
    return safeNormalize(axis - N * glm::dot(N, axis), axis);
}

}  // namespace

dvec3 safeNormalize(const dvec3& v, const dvec3& fallback) {
    const double len2 = glm::dot(v, v);
    return len2 < kMinLength2 ? fallback : v / std::sqrt(len2);
}

dvec3 srgbToLinear(const dvec3& c) {
    return {srgbDecode(c.x), srgbDecode(c.y), srgbDecode(c.z)};
}

dvec3 pointLightRadiance(const dvec3& lightColor, const dvec3& lightPos, const dvec3& worldPos) {
    const dvec3 d = lightPos - worldPos;
    return lightColor / std::max(glm::dot(d, d), kMinDistance2);
}

dvec3 halfwayVector(const dvec3& L, const dvec3& V) {
    return safeNormalize(L + V, dvec3(0.0));
}

double lambertCosine(const dvec3& N, const dvec3& L) {
    return std::max(glm::dot(N, L), 0.0);
}

double distributionGGX(const dvec3& N, const dvec3& H, double roughness) {
    const double a = roughness * roughness;
    const double a2 = std::max(a * a, kMinAlpha2);
    const double NdotH = std::max(glm::dot(N, H), 0.0);
    const double NdotH2 = NdotH * NdotH;
    // NdotH2 * (a2 - 1) + 1, grouped so that nothing cancels at NdotH = 1 (see solution.glsl).
    const double d = (1.0 - NdotH2) + NdotH2 * a2;
    return a2 / (kPi * d * d);
}

double geometrySchlickGGX(double NdotX, double roughness) {
    const double x = std::max(NdotX, 0.0);
    const double k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
    return x / (x * (1.0 - k) + k);
}

double geometrySmith(const dvec3& N, const dvec3& V, const dvec3& L, double roughness) {
    return geometrySchlickGGX(std::max(glm::dot(N, V), 0.0), roughness) *
           geometrySchlickGGX(std::max(glm::dot(N, L), 0.0), roughness);
}

dvec3 baseReflectivity(const dvec3& albedo, double metallic) {
    return glm::mix(dvec3(kDielectricF0), albedo, metallic);
}

dvec3 fresnelSchlick(double cosTheta, const dvec3& F0) {
    return F0 + (1.0 - F0) * std::pow(std::clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}

dvec3 cookTorranceSpecular(const dvec3& N, const dvec3& V, const dvec3& L, const dvec3& F0,
                           double roughness, DenominatorGuard guard) {
    const dvec3 H = halfwayVector(L, V);
    const double D = distributionGGX(N, H, roughness);
    const double G = geometrySmith(N, V, L, roughness);
    const dvec3 F = fresnelSchlick(std::max(glm::dot(H, V), 0.0), F0);
    const double denom = 4.0 * std::max(glm::dot(N, V), 0.0) * std::max(glm::dot(N, L), 0.0);
    return D * G * F /
           (guard == DenominatorGuard::Floor ? std::max(denom, kSpecularDenomFloor)
                                             : denom + kLessonDenomEpsilon);
}

dvec3 cookTorranceBRDF(const dvec3& N, const dvec3& V, const dvec3& L, const dvec3& albedo,
                       double metallic, double roughness, DenominatorGuard guard) {
    const dvec3 F0 = baseReflectivity(albedo, metallic);
    const dvec3 H = halfwayVector(L, V);
    const dvec3 F = fresnelSchlick(std::max(glm::dot(H, V), 0.0), F0);
    const dvec3 kD = (1.0 - F) * (1.0 - metallic);
    return kD * albedo / kPi + cookTorranceSpecular(N, V, L, F0, roughness, guard);
}

dvec3 reflectedRadiance(const dvec3& P, const dvec3& N, const dvec3& V, const dvec3& albedo,
                        double metallic, double roughness, double ao, const PointLight* lights,
                        int lightCount, DenominatorGuard guard) {
    dvec3 Lo(0.0);
    for (int i = 0; i < lightCount; ++i) {
        const dvec3 L = safeNormalize(lights[i].position - P, dvec3(0.0));
        const dvec3 radiance = pointLightRadiance(lights[i].color, lights[i].position, P);
        Lo += cookTorranceBRDF(N, V, L, albedo, metallic, roughness, guard) * radiance *
              lambertCosine(N, L);
    }
    return Lo + kAmbient * albedo * ao;
}

dvec3 displayEncode(const dvec3& hdr) {
    const dvec3 h = glm::max(hdr, dvec3(0.0));
    const dvec3 c = h / (h + 1.0);
    return glm::pow(c, dvec3(1.0 / 2.2));
}

dvec3 normalFromMap(const dvec3& N, const dvec4& tangent, const dvec3& mapTexel) {
    const dvec3 n = mapTexel * 2.0 - 1.0;
    const dvec3 t = dvec3(tangent);
    const dvec3 T = safeNormalize(t - N * glm::dot(N, t), perpendicularTo(N));
    const dvec3 B = glm::cross(N, T) * (tangent.w < 0.0 ? -1.0 : 1.0);
    return safeNormalize(T * n.x + B * n.y + N * n.z, N);
}

}  // namespace pbrlab::ref
