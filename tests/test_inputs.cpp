// Every input the contract gives a step, graded over its range (docs/grading.md, "Every input
// the contract gives, graded over its range"): the inputs callers produce with float rounding,
// counts above the largest graded everywhere, and every value the host provides that a step's
// code reads, graded at two values or more.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "course/autograder.h"
#include "gl/context.h"
#include "grading/grade_step.h"
#include "grading/stability.h"
#include "render/converge.h"
#include "render/evaluate.h"
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
    EXPECT_EQ(r.modules[0].status, GradeStatus::Failed);
    EXPECT_NE(r.modules[0].message.find("NaN on an input its callers produce"), std::string::npos)
        << r.modules[0].message;
    EXPECT_NE(r.modules[0].message.find("your step 9 fresnel"), std::string::npos)
        << r.modules[0].message;
    // Stepwise, the student's specular is right: the reference fresnel is clamped.
    o.cumulative = false;
    const GradeReport stepwise = gradeSubmission(modules, paths, o);
    EXPECT_EQ(stepwise.modules[0].status, GradeStatus::Passed) << stepwise.modules[0].message;
}

// Per step, the host values its code can read and the values the grade gave each
// (StepResult::hostValues, recorded as its checks render), printed as a table
// (docs/grading.md, "What the host provides"). Each read value is given two values or more (a
// value graded at one only could be hard-coded unseen: split_sum's uPrefilterMaxLod was), and
// each reaches the ends of what the host itself can produce, taken from the host's code, not
// the grader's: NUM_LIGHTS 1 to kMaxSceneLights for a step whose program reads the lights; the
// maps' sizes at the ends of --error-budget's ladder (iblLadder) and at LearnOpenGL's
// (`precompute --learnopengl`), uPrefilterMaxLod from 0 to the full chain of the ladder's
// largest prefilter; a float parameter at both ends of its range.
TEST(Inputs, EveryHostValueAStepReadsIsGradedAtTwoValuesOrMore) {
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer{paths};
    GradeSettings settings;
    settings.feedback = false;
    settings.robustness = false;
    // What the host can produce (core/render/converge.cpp, core/ibl/settings.cpp,
    // core/assets/scene.h).
    const std::vector<IblSettings> ladder = iblLadder();
    const IblSettings defaults, learnOpenGl = IblSettings::learnOpenGl();
    auto ends = [&](auto member) {
        int lo = defaults.*member, hi = defaults.*member;
        for (const IblSettings& s : ladder)
            lo = std::min(lo, s.*member), hi = std::max(hi, s.*member);
        lo = std::min(lo, learnOpenGl.*member), hi = std::max(hi, learnOpenGl.*member);
        return std::pair{lo, hi};
    };
    const auto [irradianceLo, irradianceHi] = ends(&IblSettings::irradianceSize);
    const auto [prefilterLo, prefilterHi] = ends(&IblSettings::prefilterSize);
    const auto [environmentLo, environmentHi] = ends(&IblSettings::environmentSize);
    const int maxLodHi = int(std::log2(prefilterHi));  // --prefilter-mips: the full chain
    // "sky 128x128 (5 mips)" -> 128 (the width); "4" -> 4.
    auto numbers = [](const std::set<std::string>& values, bool size) {
        std::set<int> out;
        for (const std::string& v : values) {
            const size_t x = v.rfind('x');
            if (!size) {
                out.insert(std::stoi(v));
            } else if (x != std::string::npos && x > 0) {
                size_t start = x;
                while (start > 0 && std::isdigit(static_cast<unsigned char>(v[start - 1]))) --start;
                out.insert(std::stoi(v.substr(start, x - start)));
            }
        }
        return out;
    };
    auto list = [](const std::set<int>& values) {
        std::string s;
        for (int v : values) s += (s.empty() ? "" : ", ") + std::to_string(v);
        return s;
    };
    auto includes = [](const std::set<int>& values, std::initializer_list<int> wanted) {
        for (int v : wanted)
            if (!values.count(v)) return false;
        return true;
    };
    int graded = 0;
    for (const LoadedModule& m : modules.modules()) {
        const ModuleDesc& d = *m.desc;
        // What the step's program declares and the host sets: the lights in every program, the
        // environment and the maps where the step is given them, its parameters.
        std::vector<std::string> visible = {"NUM_LIGHTS", "uLightPositions", "uLightColors"};
        if (d.needs & NeedsEnvironment) visible.push_back("uEnvironment");
        if (d.needs & NeedsPrecomputedMaps)
            for (const char* name :
                 {"uIrradianceMap", "uPrefilterMap", "uPrefilterMaxLod", "uBrdfLut"})
                visible.push_back(name);
        for (const ParamDecl& p : d.params) visible.push_back(p.uniformName());
        // What its reference solution and view read; a view that sums the lights through an
        // earlier step's function (tonemap's) reads them too: its program does.
        const std::string code =
            readText(m.sourceDir / "solution.glsl") + readText(m.sourceDir / "view.glsl");
        const bool readsLights = readsSceneLights(renderer, m, {}, 7);
        auto read = [&](const std::string& name) {
            return code.find(name) != std::string::npos ||
                   (readsLights &&
                    (name == "NUM_LIGHTS" || name == "uLightPositions" || name == "uLightColors"));
        };
        const StepResult r = gradeStep(renderer, m, paths, {}, settings);
        EXPECT_TRUE(r.passed) << d.id;
        std::string line;
        bool readsAny = false;
        for (const std::string& name : visible) {
            const auto it = r.hostValues.find(name);
            std::set<std::string> values =
                it == r.hostValues.end() ? std::set<std::string>() : it->second;
            std::string shown;
            // An estimator's count is graded by convergence (grading/estimator_convergence.cpp),
            // whose renders are not recorded: its counts are the spec's.
            if (d.estimator && name == "u_" + d.estimator->samplesParam) {
                std::set<int> counts(d.estimator->sampleCounts.begin(),
                                     d.estimator->sampleCounts.end());
                counts.insert(d.estimator->highCounts.begin(), d.estimator->highCounts.end());
                line += " " + name + ": " + list(counts) + " (by convergence);";
                readsAny = true;
                continue;
            }
            if (!read(name)) {
                // Not read by the reference: graded where a student's program reads it (the
                // lights: gradeValues asks the student's program too).
                std::string v;
                if (name == "NUM_LIGHTS")
                    v = list(numbers(values, false));
                else if (name.rfind("uLight", 0) == 0)
                    v = std::to_string(values.size()) + " sets";
                else if (name == "uBrdfLut" || name.rfind("u_", 0) == 0)
                    for (const std::string& x : values) v += (v.empty() ? "" : ", ") + x;
                else
                    v = list(numbers(values, name != "uPrefilterMaxLod"));
                line += " (" + name + ": " + v + ");";
                continue;
            }
            readsAny = true;
            if (name == "uLightPositions" || name == "uLightColors") {
                shown = std::to_string(values.size()) + " sets";
            } else if (name == "NUM_LIGHTS" || name == "uPrefilterMaxLod") {
                const std::set<int> v = numbers(values, false);
                shown = list(v);
                if (name == "NUM_LIGHTS") {
                    EXPECT_TRUE(!readsLights ||
                                (includes(v, {1, int(kMaxSceneLights)}) && v.size() >= 5))
                        << d.id << " NUM_LIGHTS " << shown;
                } else {
                    EXPECT_TRUE(includes(v, {0, defaults.prefilterMips - 1, maxLodHi}))
                        << d.id << " uPrefilterMaxLod " << shown;
                }
            } else if (name == "uBrdfLut") {
                for (const std::string& v : values) shown += (shown.empty() ? "" : ", ") + v;
                for (const IblSettings& s : {defaults, learnOpenGl}) {
                    const std::string size =
                        std::to_string(s.lutWidth) + "x" + std::to_string(s.lutHeight);
                    EXPECT_TRUE(values.count(size)) << d.id << " uBrdfLut " << shown;
                }
            } else if (name == "uEnvironment" || name == "uIrradianceMap" ||
                       name == "uPrefilterMap") {
                const std::set<int> v = numbers(values, true);
                shown = list(v) + " square";
                if (name == "uEnvironment") {
                    // The default, one below anything the host builds (where a size written in
                    // shows) and, for code that queries a texture's size (the only code that
                    // can tell it from the default), the largest the host builds.
                    bool queries = false;
                    for (const char* q : {"textureSize", "textureQueryLevels", "textureQueryLod"})
                        queries = queries || code.find(q) != std::string::npos;
                    EXPECT_TRUE(v.count(defaults.environmentSize) && *v.begin() < environmentLo &&
                                (!queries || v.count(environmentHi)))
                        << d.id << " uEnvironment " << shown;
                    if (!queries)
                        shown +=
                            " (" + std::to_string(environmentHi) + ": for code that queries it)";
                } else {
                    const auto [lo, hi] = name == "uIrradianceMap"
                                              ? std::pair{irradianceLo, irradianceHi}
                                              : std::pair{prefilterLo, prefilterHi};
                    EXPECT_TRUE(includes(v, {lo, hi})) << d.id << " " << name << " " << shown;
                }
            } else {
                for (const std::string& v : values) shown += (shown.empty() ? "" : ", ") + v;
                for (const ParamDecl& p : d.params)
                    if (p.uniformName() == name && p.type == ParamType::Int)
                        shown = list(numbers(values, false));
                if (shown.size() > 60) shown = std::to_string(values.size()) + " values";
                for (const ParamDecl& p : d.params)
                    if (p.uniformName() == name && p.type == ParamType::Float) {
                        EXPECT_TRUE(values.count(p.format(glm::dvec3(p.min))) &&
                                    values.count(p.format(glm::dvec3(p.max))))
                            << d.id << " " << name << " " << shown;
                    }
            }
            line += " " + name + ": " + shown + ";";
            EXPECT_GE(values.size(), 2u) << d.id << " reads " << name;
        }
        std::printf("[ measured ] %-12s%s\n", d.id.c_str(), line.c_str());
        graded += readsAny;
    }
    // fresnel (u_cosine), reflectance and tonemap (the lights), hammersley (u_samples),
    // split_sum (the maps), the estimators (uEnvironment, u_samples); the light-direction
    // parameters move the scene's light, which the host reads.
    EXPECT_GE(graded, 8);
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
