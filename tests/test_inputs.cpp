// Every input the contract gives a step, graded over its range (docs/grading.md, "Every input
// the contract gives, graded over its range"): the inputs callers produce with float rounding,
// counts above the largest graded everywhere, and every value the host provides that a step's
// code reads, graded at two values or more.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <sstream>

#include "course/autograder.h"
#include "gl/context.h"
#include "grading/grade_step.h"
#include "grading/stability.h"
#include "steps/contract.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

std::string readText(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// The names the contract lets a step's code read from the host (DESIGN.md, "Assignment
// contract"), besides its parameters' u_<name>.
const std::vector<std::string> kContractHostNames = {
    "NUM_LIGHTS",     "uLightPositions", "uLightColors",     "uEnvironment",
    "uIrradianceMap", "uPrefilterMap",   "uPrefilterMaxLod", "uBrdfLut"};

}  // namespace

TEST(Inputs, CountsAreGradedAboveTheLargestGradedEverywhere) {
    auto values = [](int max) { return exercisedValues(intParam("samples", 64, 1, max, "")); };
    const std::vector<std::string> all = values(65536);
    for (const char* v :
         {"samples=1", "samples=7", "samples=1024", "samples=4096", "samples=65536"})
        EXPECT_NE(std::find(all.begin(), all.end(), v), all.end()) << v;
    const std::vector<std::string> upTo4096 = values(4096);
    EXPECT_NE(std::find(upTo4096.begin(), upTo4096.end(), "samples=4096"), upTo4096.end());
    EXPECT_EQ(std::find(upTo4096.begin(), upTo4096.end(), "samples=65536"), upTo4096.end());
    for (const std::string& v : values(1024)) EXPECT_NE(v, "samples=4096");
}

TEST(Inputs, CallerSurfacesHoldWhatCallersProduceAndNotTheExtremes) {
    const ExtremeSet set = callerSurfaces(0.05);
    constexpr double ulp = std::numeric_limits<float>::epsilon();
    bool cosineAbove1 = false, vIsL = false, grazingView = false, grazingLight = false,
         belowHorizon = false;
    for (size_t i = 0; i < set.labels.size(); ++i) {
        const Surface& s = set.surfaces[i];
        const glm::vec3 N(s.normal), V(s.view), L(s.light);
        for (const glm::vec3& u : {N, V, L})
            EXPECT_NEAR(glm::length(glm::dvec3(u)), 1.0, 3 * ulp) << set.labels[i];
        cosineAbove1 = cosineAbove1 || glm::dot(N, V) > 1.0f;
        vIsL = vIsL || s.view == s.light;
        grazingView = grazingView || glm::dot(N, V) == 0.0f;
        grazingLight = grazingLight || glm::dot(N, L) == 0.0f;
        belowHorizon = belowHorizon || glm::dot(N, V) < 0.0f;
        // Not the robustness inputs: V = -L, roughness 0.
        EXPECT_GT(glm::dot(s.view, s.light), -0.999) << set.labels[i];
        EXPECT_GT(s.roughness, 0) << set.labels[i];
    }
    EXPECT_TRUE(cosineAbove1 && vIsL && grazingView && grazingLight && belowHorizon);
}

// fresnel's callers pass max(dot(H, V), 0.0), 1 + 1 ulp when V = L: an unclamped Schlick
// factor is NaN there. In --cumulative, the step whose view breaks names the student's step
// that causes it (specular's reference code, the student's fresnel).
TEST(Inputs, ANaNThroughAnEarlierStepNamesThatStep) {
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    test::TempDir kit;
    kit.write("fresnel.glsl", readText(fs::path(PBRLAB_SOURCE_DIR) /
                                       "tests/variants/fresnel/mistake_no_clamp.glsl"));
    kit.write("specular.glsl", R"(
vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)
{
    vec3 H = halfwayVector(L, V);
    vec3 F = fresnelSchlick(max(dot(H, V), 0.0), F0);
    float denom = 4.0 * max(dot(N, V), 0.0) * max(dot(N, L), 0.0);
    return distributionGGX(N, H, roughness) * geometrySmith(N, V, L, roughness) * F /
           max(denom, 1e-4);
}
)");
    GradeOptions o;
    o.submission = fs::canonical(kit.path);
    o.modules = {"specular"};
    o.cumulative = true;
    o.timeoutSeconds = 300;
    const GradeReport r = gradeSubmission(modules, paths, o);
    ASSERT_EQ(r.modules.size(), 1u);
    EXPECT_EQ(r.modules[0].status, "failed");
    EXPECT_NE(r.modules[0].message.find("NaN on an input its callers produce"), std::string::npos)
        << r.modules[0].message;
    EXPECT_NE(r.modules[0].message.find("your step 9 fresnel"), std::string::npos)
        << r.modules[0].message;
    // Stepwise, the student's specular is right: the reference fresnel is clamped.
    o.cumulative = false;
    const GradeReport stepwise = gradeSubmission(modules, paths, o);
    EXPECT_EQ(stepwise.modules[0].status, "passed") << stepwise.modules[0].message;
}

// Per step, the host values its code reads (the reference solution and the view: the contract's
// names and its parameters' uniforms), each given at least two values by the grade's values
// checks (StepResult::hostValues, recorded as they render). A value graded at one only could be
// hard-coded unseen (split_sum's uPrefilterMaxLod was).
TEST(Inputs, EveryHostValueAStepReadsIsGradedAtTwoValuesOrMore) {
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer{paths};
    GradeSettings settings;
    settings.feedback = false;
    settings.robustness = false;
    int graded = 0;
    for (const LoadedModule& m : modules.modules()) {
        const ModuleDesc& d = *m.desc;
        if (d.estimator) continue;  // 17-20: graded by convergence (grading/estimator_band.cpp)
        const std::string code =
            readText(m.sourceDir / "solution.glsl") + readText(m.sourceDir / "view.glsl");
        std::vector<std::string> reads;
        for (const std::string& name : kContractHostNames)
            if (code.find(name) != std::string::npos) reads.push_back(name);
        for (const ParamDecl& p : d.params)
            if (code.find(p.uniformName()) != std::string::npos) reads.push_back(p.uniformName());
        std::string line = d.id + ":";
        if (reads.empty()) {
            std::printf("[ measured ] %s none\n", line.c_str());
            continue;
        }
        const StepResult r = gradeStep(renderer, m, paths, {}, settings);
        EXPECT_TRUE(r.passed) << d.id;
        for (const std::string& name : reads) {
            const auto it = r.hostValues.find(name);
            const size_t count = it == r.hostValues.end() ? 0 : it->second.size();
            line += " " + name + " (" + std::to_string(count) + " values)";
            EXPECT_GE(count, 2u) << d.id << " reads " << name;
        }
        std::printf("[ measured ] %s\n", line.c_str());
        ++graded;
    }
    // fresnel (u_cosine), reflectance (the lights), hammersley (u_samples), split_sum (the maps)
    // today; the light-direction parameters move the scene's light, which the host reads.
    EXPECT_GE(graded, 4);
}

// What the caller set's "1 +- 2 ulps" rests on: unit vectors the GPU normalises in float
// (halfway's view is normalize(L + V), the reference solution's) on 65536 random pairs.
TEST(Inputs, VectorsNormalisedInFloatAreWithinTwoUlpsOfUnitLength) {
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer{paths};
    const LoadedModule& halfway = modules.find("halfway");
    DomainRandom random(7);
    std::vector<Surface> surfaces(65536);
    for (Surface& s : surfaces) {
        s.covered = true;
        s.view = random.direction();
        do s.light = random.direction();
        while (glm::dot(s.view, s.light) < -0.9);
    }
    const ParamValues params(halfway.desc->params);
    const Scene scene = loadScene(paths.scene(halfway.desc->scene));
    const RenderResult r = renderer.renderSurfaces(halfway, params, scene, {}, surfaces, 256, 256);
    double worst = 0;
    for (size_t i = 0; i < surfaces.size(); ++i) {
        const glm::dvec3 h(r.value.pixels[i * 4], r.value.pixels[i * 4 + 1],
                           r.value.pixels[i * 4 + 2]);
        worst =
            std::max(worst, std::abs(glm::length(h) - 1) / std::numeric_limits<float>::epsilon());
    }
    std::printf("[ measured ] | |normalize(L + V)| - 1 | <= %.3g ulps over %zu pairs\n", worst,
                surfaces.size());
    EXPECT_LE(worst, 2.0);
}
