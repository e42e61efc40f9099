#include "pbrlab/contract.h"

#include <cstdio>
#include <set>

#include "pbrlab/error.h"

namespace pbrlab {

std::string ContractStep::folder() const {
    char buf[8];
    std::snprintf(buf, sizeof buf, "%02d-", step);
    return buf + id;
}

const std::vector<ContractStep>& contractSteps() {
    static const std::vector<ContractStep> steps = {
        {1, "albedo", "direct", "vec3 srgbToLinear(vec3 c)", {}},
        {2,
         "radiance",
         "direct",
         "vec3 pointLightRadiance(vec3 lightColor, vec3 lightPos, vec3 worldPos)",
         {}},
        {3, "halfway", "direct", "vec3 halfwayVector(vec3 L, vec3 V)", {}},
        {4, "ndotl", "direct", "float lambertCosine(vec3 N, vec3 L)", {}},
        {5, "ndf", "direct", "float distributionGGX(vec3 N, vec3 H, float roughness)", {}},
        {6, "g1", "direct", "float geometrySchlickGGX(float NdotX, float roughness)", {}},
        {7,
         "smith",
         "direct",
         "float geometrySmith(vec3 N, vec3 V, vec3 L, float roughness)",
         {"g1"}},
        {8, "f0", "direct", "vec3 baseReflectivity(vec3 albedo, float metallic)", {}},
        {9, "fresnel", "direct", "vec3 fresnelSchlick(float cosTheta, vec3 F0)", {}},
        {10,
         "specular",
         "direct",
         "vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)",
         {"halfway", "ndf", "smith", "fresnel"}},
        {11,
         "brdf",
         "direct",
         "vec3 cookTorranceBRDF(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float "
         "roughness)",
         {"f0", "halfway", "fresnel", "specular"}},
        {12,
         "reflectance",
         "direct",
         "vec3 reflectedRadiance(vec3 P, vec3 N, vec3 V, vec3 albedo, float metallic, float "
         "roughness, float ao)",
         {"radiance", "ndotl", "brdf"}},
        {13, "tonemap", "direct", "vec3 displayEncode(vec3 hdr)", {}},
        {14, "normalmap", "direct", "vec3 normalFromMap(vec3 N, vec4 tangent, vec3 mapTexel)", {}},
        {15, "hammersley", "ibl", "vec2 hammersley(uint i, uint n)", {}},
        {16, "importance", "ibl", "vec3 importanceSampleGGX(vec2 Xi, vec3 N, float roughness)", {}},
        {17,
         "mc_specular",
         "ibl",
         "vec3 specularIBLReference(vec3 N, vec3 V, vec3 F0, float roughness, uint sampleCount)",
         {"hammersley", "importance", "fresnel"}},
        {18, "irradiance", "ibl", "vec3 irradianceAt(vec3 N)", {}},
        {19,
         "prefilter",
         "ibl",
         "vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)",
         {"hammersley", "importance", "ndf"}},
        {20,
         "brdf_lut",
         "ibl",
         "vec2 integrateBRDF(float NdotV, float roughness, uint sampleCount)",
         {"hammersley", "importance"}},
        {21,
         "split_sum",
         "ibl",
         "vec3 ambientIBL(vec3 N, vec3 V, vec3 albedo, float metallic, float roughness, float ao)",
         {"f0"}},
    };
    return steps;
}

std::string contractPrototypes() {
    std::string text =
        "// Every contract function, declared before any is defined: any step may call any.\n";
    for (const auto& s : contractSteps()) text += s.function + ";\n";
    return text + kFresnelSchlickRoughness + ";\n";
}

const ContractStep* findContractStep(const std::string& id) {
    for (const auto& s : contractSteps())
        if (s.id == id) return &s;
    return nullptr;
}

std::vector<const ContractStep*> contractClosure(const std::string& id,
                                                 const std::vector<std::string>& extra) {
    const ContractStep* self = findContractStep(id);
    if (!self) throw Error("'" + id + "' is not a contract step id");
    std::set<int> wanted;
    std::vector<std::string> pending = extra;
    pending.push_back(id);
    for (const auto& s : contractSteps())
        if (s.lab == self->lab && s.step < self->step) pending.push_back(s.id);
    while (!pending.empty()) {
        std::string next = pending.back();
        pending.pop_back();
        const ContractStep* s = findContractStep(next);
        if (!s) throw Error("'" + next + "' is not a contract step id");
        if (!wanted.insert(s->step).second) continue;
        pending.insert(pending.end(), s->calls.begin(), s->calls.end());
    }
    std::vector<const ContractStep*> result;
    for (const auto& s : contractSteps())
        if (wanted.count(s.step)) result.push_back(&s);
    return result;
}

}  // namespace pbrlab
