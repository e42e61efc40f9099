// The lesson's shading formulas with every part at an exponent of its own, for the named-term
// feedback of the steps built on them (pbrlab/named_terms.h): the GGX distribution, Smith's G1,
// Schlick's Fresnel, the Cook-Torrance lobe D G F / (4 N.L N.V) with the diffuse term
// kD albedo / pi, and the IBL estimators' weight G V.H / (N.H N.V). With every exponent at its
// default each function is the reference's (pbrlab/reference.h).
#pragma once

#include <glm/glm.hpp>

#include "pbrlab/named_terms.h"

namespace pbrlab {

// The exponent of each part (defaults: the reference). Switches (a part written another way,
// a term of a sum present or not) are 1 or 0.
struct ShadingKnobs {
    // Cook-Torrance's specular lobe D G F / (4 N.L N.V) and its parts.
    double D = 1, G1V = 1, G1L = 1, F = 1, F0 = 0;
    double four = -1, NL = -1, NV = -1;
    double alphaPower = 2;              // alpha = roughness^alphaPower
    double alpha2 = 1;                  // alpha^2 in D's numerator (as a power of alpha^2)
    double NHpower = 2;                 // (N.H)^2 in D's denominator
    double denominator = 2;             // D's denominator squared
    double schlick = 5;                 // the Schlick factor (1 - cos)^5
    double oneMinusF0 = 1;              // (1 - F0) in front of it
    double f0TimesSchlick = 0;          // F0 + F0 (1 - cos)^5
    double fresnelAtNdotV = 0;          // F at N.V instead of H.V
    double f0ForF = 0;                  // F0 where F belongs
    double NX = 1;                      // N.X in G1's numerator
    double kChoice = 0;                 // another remapping of k (kRemappings)
    double kComplement = 0;             // 1 - k in place of k
    double g1vTwice = 0, g1lTwice = 0;  // G1(N.V) for the light too, or G1(N.L) for the view
    double unnormalisedH = 0;           // H = L + V where normalize(L + V) belongs
    // The IBL estimators' weight G (V.H) / ((N.H)(N.V)).
    double VH = 1, NH = -1;
    // The diffuse part kD albedo / pi, and the BRDF's sum.
    double kD = 1, metal = 1, albedo = 1, pi = -1, diffuse = 1, specular = 1, cosine = 0;
};

// G1's remapping of roughness to k: the direct one (roughness + 1)^2 / 8 first, the IBL one
// roughness^2 / 2 second, then others people write.
struct KRemapping {
    const char* name;
    double (*k)(double roughness);
};
const std::vector<KRemapping>& kRemappings();

// G1 = N.X / (N.X (1 - k) + k). `own`: the step's remapping (0 direct, 1 IBL); k.kChoice
// replaces it (-1 the direct one, i > 0 kRemappings()[i]).
double shadingG1(double NdotX, double roughness, const ShadingKnobs& k, int own);
// GGX's D at N.H.
double shadingGgx(double NdotH, double roughness, const ShadingKnobs& k);
// Schlick's F at `cosine`.
glm::dvec3 shadingFresnel(double cosine, const glm::dvec3& F0, const ShadingKnobs& k);

// D G F / (4 N.L N.V) and kD albedo / pi at one light direction (ref::cookTorranceBRDF).
struct Lobe {
    glm::dvec3 specular, diffuse;
};
Lobe cookTorranceLobe(const Surface& s, const glm::dvec3& L, const ShadingKnobs& k);
// The BRDF: diffuse + specular, times N.L^k.cosine (0 in the reference).
glm::dvec3 shadingBrdf(const Surface& s, const glm::dvec3& L, const ShadingKnobs& k);

// The terms of the lobe (`whole`: the lobe is the step's value, so a missing factor is said as
// a ratio), shared by specular, brdf and reflectance.
KnobbedTerms<ShadingKnobs> specularLobeTerms(bool whole);
// The terms of kD albedo / pi and of the sum diffuse + specular.
KnobbedTerms<ShadingKnobs> diffuseTerms();
// G1 = N.X / (N.X (1 - k) + k) with 1 - k in place of k.
KnobbedTerm<ShadingKnobs> kSwappedTerm();
// The weight V.H / (N.H N.V) that dividing D G F N.L / (4 N.L N.V) by the pdf D N.H / (4 V.H)
// leaves, as a whole: its three factors missing at once.
KnobbedTerm<ShadingKnobs> pdfWeightTerm();
// The estimators' weight G V.H / (N.H N.V) (`weight` says where it appears) and the direct
// light's remapping where IBL has its own: what mc_specular and brdf_lut share.
KnobbedTerms<ShadingKnobs> estimatorWeightTerms(const std::string& weight);

// The direct light's remapping k = (roughness + 1)^2 / 8 where IBL has k = roughness^2 / 2.
KnobbedTerm<ShadingKnobs> directRemappingTerm();

// A light's falloff 1/d^e as a message writes it ("1/d^3", "no falloff with distance").
inline std::string falloffText(double e) {
    return e == 0  ? std::string("no falloff with distance")
           : e < 0 ? "1/d^" + exponentText(-e)
                   : "d^" + exponentText(e);
}

}  // namespace pbrlab
