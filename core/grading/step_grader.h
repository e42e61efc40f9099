// The grader of one step behind gradeStep, private to core/grading. Its checks are defined by
// responsibility, one file each:
//   grade_step.cpp       the order of the checks, the verdict, stages and their times
//   values.cpp           values against the reference's band: the probe, the scenes (the
//                        sphere grid among a step's declared cases), random inputs, every
//                        exercised parameter value, coloured lights
//   estimator*.cpp       estimators by convergence to the converged integral (estimator.h)
//   sun.cpp              an environment with a real sun
//   linearity.cpp        linear in radiance: steps that read the environment
//   checks.cpp           the contract (what a step may read), invariants, robustness
//   failure_message.cpp  the failure message and the mistake named from the error
#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "grading/grade_step.h"

namespace pbrlab::step_grading {

constexpr int kRowWidth = 64;  // surface sets are uploaded as rows of 64 points

// The IBL settings of the maps grading reads: the defaults, as every RenderRequest of the
// grader leaves them, so that the references read the maps the views read.
inline const IblSettings kGradingIbl{};

// A number in a report line (4 significant digits unless told).
std::string number(double v, int digits = 4);

// Surfaces as a width-64 grid, padded with uncovered points.
struct Grid {
    std::vector<Surface> surfaces;
    int width = kRowWidth, height = 1;
};
Grid grid(std::vector<Surface> surfaces);

// The first `count` pixels of a rendered value image (RGBA32F), as the values a check compares.
std::vector<glm::dvec3> pointValues(const Image& value, size_t count);

// The module's parameters at their defaults, then these assignments ("samples=7").
ParamValues withSets(const ModuleDesc& d, const std::vector<std::string>& set);

// A check of values against a band, with what feedback needs if it fails.
struct ValuesRun {
    CheckReport report;
    std::vector<Surface> surfaces;  // the inputs, as the view saw them
    Image value;
    Band band;
    Scene scene;
    ParamValues params;
    bool fromScene = false;  // the scene's G-buffer (else the surfaces were uploaded)
    int width = 0, height = 0;
    int worstIndex = -1;         // the point outside the band by most
    double outlierFraction = 0;  // of the band (Tolerance::outlierFraction)
    // Which failed run the feedback reads (StepGrader::keep), in this order. The patterns and
    // term fits are measured on points drawn alone on the ordinary skies, so a run there comes
    // first. A sun or the picture come next: they carry their own cause, and a mistake that is
    // wrong everywhere is only blurred there by the sun or the derivatives (|N.L| at a coarse
    // mip went unnamed). A count above the graded ones comes last: the feedback renders its
    // candidates at the failing run's count (65536 samples made mc_specular's feedback take 10 s).
    enum class Tier { Ordinary, LabUse, AboveGradedCounts };
    Tier tier = Tier::Ordinary;
    // The cause, when the check itself can tell it from its error (a sun's light dropped,
    // screen-space derivatives): the feedback names it instead of looking for a pattern.
    std::string cause;
};

// The report of a values check from its comparison; `probe` or `width` say how its worst
// point is located (probe axes, a pixel, or only its inputs).
CheckReport reportFor(const std::string& name, const ModuleDesc& d, const Comparison& c,
                      const std::vector<Surface>& surfaces, double outlierFraction,
                      const Probe* probe, int width);

// The direction of the brightest texel of a cube's finest level (grading/sun.cpp).
glm::dvec3 brightestDirection(const CubeSampler& cube);
// Random points of the domain turned to face the sun (grading/sun.cpp).
std::vector<Surface> sunFacingSurfaces(const ModuleDesc& d, std::uint64_t seed, int count,
                                       const glm::dvec3& sun, double maxRoughness);
constexpr int kSunFacingPoints = 128;
// Why a check on points facing the sun failed, from the shape of its error: too low nearly
// everywhere (bright light dropped or limited), too high, or both ways (the sun sampled too
// coarsely), when `rightWithoutSun` (every check without a sun passed: the sun is the cause);
// else which way the points are off, without a claim. "" when nothing is outside.
std::string sunCause(const Image& value, const std::vector<Surface>& points, const Band& band,
                     int components, bool rightWithoutSun);

// "depends on screen derivatives: ..." with what the pixels drawn alone measured
// (grading/derivatives.cpp).
std::string derivativesCause(int outsideAlone, int comparedAlone);

class StepGrader {
public:
    StepGrader(LabRenderer& renderer, const LoadedModule& m, const DataPaths& paths,
               const StudentSource& source, const GradeSettings& settings)
        : renderer_(renderer),
          m_(m),
          d_(*m.desc),
          paths_(paths),
          source_(source),
          settings_(settings) {}

    StepResult run();
    // The estimator's statistical checks alone (convergence on every environment, the counts
    // above): what the false-failure measurement repeats per seed (tests/test_estimator_seeds.cpp).
    // `parts`: which of them (StatisticsPart bits; all by default), so that a sweep of many
    // seeds can measure one.
    enum StatisticsPart : unsigned { Convergence = 1, Sun = 2, Picture = 4 };
    StepResult runEstimatorStatistics(unsigned parts = Convergence | Sun | Picture);

private:
    struct Stopped {};

    // grading/grade_step.cpp
    void record(const CheckReport& c);
    void stage(const std::string& what);

    // grading/values.cpp
    // `ibl`: the settings of the precomputed maps the view reads (and the reference with it).
    ValuesRun runValues(const std::string& name, CheckCategory category, const Scene& scene,
                        const ParamValues& params, const std::vector<Surface>* surfaces, int width,
                        int height, const Probe* probe, const IblSettings& ibl = kGradingIbl);
    // Notes the host-provided values a render gave the step's program (StepResult::hostValues).
    void noteHostValues(const Scene& scene, const ParamValues& params, const IblSettings& ibl);
    void keep(ValuesRun&& run);
    // Sets run.report.showsWork when it is a values check passed that the step's stub fails
    // (the stub rendered on the same inputs, against the same band): asked until one such
    // check is found.
    void noteWork(ValuesRun& run);
    void gradeCase(const std::string& name, GradeCase::Inputs inputs, const Scene& scene,
                   const ParamValues& params, CheckCategory sceneCategory = CheckCategory::Scenes);
    void gradeValues(const Scene& scene);
    // `scene`, or for a step that reads the environment, when the scene's environment is the
    // same in every direction (the white furnace), the scene under the estimators' sky
    // (EstimatorSpec::environment): a constant environment tells no map lookup from another
    // (its direction, its mip level), so the random inputs and the host's map sizes are
    // judged there. The scene's own picture stays the scene's.
    Scene detailedScene(const Scene& scene);
    // What the host provides graded over what the host can produce: NUM_LIGHTS from 1 to the
    // most lights a scene may hold, the maps' sizes and mip count (uPrefilterMaxLod) at the ends
    // of the sizes the host makes.
    void gradeHostValues(const Scene& scene);
    // Whether the graded step's file (the student's, else the reference solution) queries a
    // texture's size or mip count (textureSize, textureQueryLevels, textureQueryLod): only such
    // code can depend on a map's size beyond the sizes graded for every step. True when it
    // cannot be read.
    bool codeQueriesTextureSize() const;
    // Which of `count` lights a step that fails with them ignores, as the message says it
    // ("ignores light 9 and up: right with NUM_LIGHTS up to 8, wrong from 9"); "" unknown.
    std::string lightsDiagnosis(const Scene& scene, int count, const Grid& g);
    Evaluation evaluatePoints(const Scene& scene, const ParamValues& params, const Grid& g,
                              const IblSettings& ibl = kGradingIbl);
    std::string hostValuesBefore(const std::string& name);
    void gradeLightCounts(const Scene& scene, const Grid& g, const Grid& few);
    void gradeMapSizes(const Scene& scene, const Grid& g);
    std::string hardCodedMapValues(const std::string& label, const IblSettings& s,
                                   const Scene& scene, const Grid& g);

    // grading/estimator_band.cpp (estimator.h)
    struct PointSet;
    struct RelativeError;
    void gradeEstimator(const Scene& scene);
    std::vector<Estimate> convergedIntegrals(const std::vector<const Surface*>& points,
                                             const Scene& judged, const ReferenceContext& context,
                                             std::uint32_t samples);
    RenderResult renderPoints(const ParamValues& params, const Scene& scene,
                              const std::vector<Surface>& surfaces, int width, int height,
                              const IblSettings& ibl = kGradingIbl);
    RenderResult renderRescaled(const std::string& scaleName, const ParamValues& params,
                                const Scene& scene, const std::vector<Surface>& surfaces, int width,
                                int height, const std::vector<Estimate>& truth,
                                const IblSettings& ibl = kGradingIbl);
    // `nameConstants`: a failed factor is said as the constant it is near ("off by pi?");
    // off where a factor is not the likely cause (a sun's light dropped).
    void rescale(const std::string& name, Image& value, const std::vector<Surface>& surfaces,
                 const std::vector<Estimate>& truth, bool nameConstants = true);

    // grading/estimator_convergence.cpp
    void gradeConvergence(const Scene& scene, const std::string& environment, bool first);
    std::vector<PointSet> convergencePointSets(const Scene& judged, const ReferenceContext& context,
                                               const std::string& onEnvironment);
    void gradeConvergenceAt(PointSet& set, const Scene& judged, const ParamValues& params, int n,
                            const std::vector<int>& counts, const std::string& onEnvironment,
                            RelativeError& error);
    void biasTest(const std::vector<PointSet>& sets, int n, const std::string& onEnvironment);
    void gradeNoise(const Scene& scene);

    // grading/estimator_counts.cpp
    void gradeHighCounts(const Scene& judged, const PointSet& probe, const PointSet& random);
    PointSet highCountPoints(const PointSet& probe, const PointSet& random) const;
    bool gradeHighCount(const Scene& judged, const PointSet& points, int n);
    void gradeEnvironmentSize(const Scene& judged, const PointSet& random);
    std::string environmentSizeCause(const Scene& judged, const Grid& g, int n,
                                     const IblSettings& ibl, const std::vector<Estimate>& truth,
                                     double errorAtN);

    // grading/estimator_picture.cpp
    void gradePicture(const Scene& scene);

    // grading/sun.cpp
    void gradeSun(const Scene& scene);
    void gradeSunAt(const Scene& judged, const PointSet& set, const std::vector<Estimate>& sunPart,
                    int n, bool cleanBefore, const std::string& on);
    void gradeSunValues(const Scene& scene);
    // The direction of the sun of `judged`'s environment (its brightest texel).
    glm::dvec3 sunDirection(const Scene& judged);
    // No deducted check failed so far: a failure from here on is the sun's to explain.
    bool noFailureSoFar() const;

    // grading/derivatives.cpp: a picture's check failed, its pixels drawn alone pass: the
    // cause (else "").
    std::string derivativesCauseOf(const ValuesRun& run);

    // grading/linearity.cpp: steps that read the environment, on multiples and sums of it
    void gradeLinearity(const Scene& scene);
    std::vector<glm::dvec3> valuesOnEnvironment(const Scene& scene, const std::string& environment,
                                                const ParamValues& params, const Grid& g);

    // grading/checks.cpp
    void checkSamplers(const Program& program);
    // A loop of the student's files that the guard cuts on the probe (shader/loop_guard.h):
    // a failed contract check naming it, and the grade stops (loopCut_).
    void checkLoopsEnd(const Scene& scene, const Program& program);
    void gradeInvariants(const Scene& scene);
    void gradeCallerInputs(const Scene& scene);
    void gradeRobustness(const Scene& scene);

    // grading/failure_message.cpp
    struct Sample;
    struct Agreement;
    struct MutantMatch;
    void explain();
    // The mistake named from the failed run `f` (result_.mistake and how it was named).
    void nameMistake(const ValuesRun& f);
    // What the error patterns read of `f`: its points, values and band, the functions on others.
    FeedbackInputs feedbackInputs(const ValuesRun& f);
    // Which of the student's calls made the first NaN or Inf at `surfaces` (the diagnosis build).
    FeedbackInputs::NonFiniteOrigin nonFiniteOrigin(const ValuesRun& f,
                                                    const std::vector<Surface>& surfaces);
    Sample sample(const ValuesRun& f);
    Image valuesOn(const ValuesRun& f, const Sample& sample, const StudentSource& source);
    Agreement agreement(const ValuesRun& f, const Sample& sample, const Image& candidate) const;
    std::string typicalMistake(const ValuesRun& f, const Sample& sample);
    MutantMatch mutantMatch(const ValuesRun& f, const Sample& sample);

    LabRenderer& renderer_;
    const LoadedModule& m_;
    const ModuleDesc& d_;
    const DataPaths& paths_;
    const StudentSource& source_;
    const GradeSettings& settings_;
    StepResult result_;
    std::unique_ptr<ValuesRun> failed_;  // the values check that failed worst
    std::string loopCut_;                // checkLoopsEnd's message, when a loop was cut
    Probe probe_;                        // the estimator's subsampled probe
    std::string stageName_;              // the stage running, and since when
    std::chrono::steady_clock::time_point stageStart_;
    double stageCpuMs_ = 0;
    bool workShown_ = false;       // a check showed work (noteWork)
    bool statisticsOnly_ = false;  // runEstimatorStatistics
    unsigned statisticsParts_ = Convergence | Sun | Picture;
    std::filesystem::path stubDir_;  // the stub's <id>.glsl, written when first needed
};

}  // namespace pbrlab::step_grading
