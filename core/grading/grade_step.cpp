// gradeStep and what the grader's files share (step_grader.h): the order of the checks, the
// verdict, the stages with their times; the values reports; the grader's public helpers.

#include "grading/grade_step.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <sstream>

#include "grading/step_grader.h"
#include "util/error.h"
#include "util/log.h"

namespace pbrlab::step_grading {

std::string number(double v, int digits) {
    std::ostringstream o;
    o.precision(digits);
    o << v;
    return o.str();
}

Grid grid(std::vector<Surface> surfaces) {
    Grid g;
    g.height = std::max(1, int((surfaces.size() + kRowWidth - 1) / kRowWidth));
    g.surfaces = std::move(surfaces);
    g.surfaces.resize(size_t(g.width) * size_t(g.height));
    return g;
}

std::vector<glm::dvec3> pointValues(const Image& value, size_t count) {
    std::vector<glm::dvec3> values;
    values.reserve(count);
    for (size_t i = 0; i < count; ++i)
        values.emplace_back(value.pixels[i * 4], value.pixels[i * 4 + 1], value.pixels[i * 4 + 2]);
    return values;
}

ParamValues withSets(const ModuleDesc& d, const std::vector<std::string>& set) {
    ParamValues values(d.params);
    for (const std::string& a : set) applyAssignment(d.params, values, a);
    return values;
}

CheckReport reportFor(const std::string& name, const ModuleDesc& d, const Comparison& c,
                      const std::vector<Surface>& surfaces, double outlierFraction,
                      const Probe* probe, int width) {
    CheckReport r;
    r.name = name;
    r.points = c.compared;
    r.outside = c.outside;
    r.nan = c.nanCount;
    r.inf = c.infCount;
    r.negative = c.negativeCount;
    r.worstExcess = c.worstExcess;
    r.worstValue = c.worstValue;
    r.worstExpected = c.worstExpected;
    r.worstLo = c.worstLo;
    r.worstHi = c.worstHi;
    r.passed = c.passes(d.nonNegative, outlierFraction);
    if (c.worstIndex >= 0) {
        r.worstAt = describeInputs(d, surfaces[size_t(c.worstIndex)]);
        if (probe)
            r.worstAt = "probe x " + number(double(c.worstX) / (probe->width - 1), 3) + " (" +
                        probe->xAxis + "), y " +
                        number(1.0 - double(c.worstY) / (probe->height - 1), 3) + " (" +
                        probe->yAxis + "): " + r.worstAt;
        else if (width > kRowWidth || surfaces.size() > size_t(kRowWidth) * 64)
            r.worstAt = "pixel (" + std::to_string(c.worstX) + ", " + std::to_string(c.worstY) +
                        "): " + r.worstAt;
    }
    std::ostringstream o;
    o << c.compared << " points: " << c.outside << " outside the band";
    if (outlierFraction > 0) o << " (" << outlierFraction * 100 << "% may be)";
    o << ", worst " << number(c.worstExcess, 3) << "x the tolerance";
    if (c.nonFinite()) o << ", " << c.nanCount << " NaN, " << c.infCount << " Inf";
    if (c.negativeCount) o << ", " << c.negativeCount << " negative";
    r.detail = o.str();
    return r;
}

StepResult StepGrader::run() {
    auto start = std::chrono::steady_clock::now();
    const Scene scene = loadScene(paths_.scene(d_.scene));
    // Compile the student's program first: a compile error is the result.
    stage("compile");
    const auto program = renderer_.programs().get(renderer_.viewRecipe(m_, source_, true, 1));
    try {
        checkSamplers(*program);
        checkLoopsEnd(scene, *program);
        gradeLinearity(scene);  // before the values: a nonlinearity explains their failures
        if (d_.estimator)
            gradeEstimator(scene);
        else {
            gradeValues(scene);
            gradeSunValues(scene);
        }
        gradeInvariants(scene);
        gradeCallerInputs(scene);
        if (settings_.robustness) gradeRobustness(scene);
    } catch (const Stopped&) {
        // stopAtFirstFailure: the verdict is known.
    }
    result_.passed = true;
    for (const CheckReport& c : result_.checks)
        if (c.deducted && !c.passed) result_.passed = false;
    if (!result_.passed) explain();
    stage("");  // the last stage's time
    result_.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::move(result_);
}

// Every check goes in through here.
void StepGrader::record(const CheckReport& c) {
    if (!c.category) throw Error("grading " + d_.id + ": check '" + c.name + "' has no category");
    result_.checks.push_back(c);
    if (settings_.stopAtFirstFailure && c.deducted && !c.passed) throw Stopped{};
}

// Each stage is also a journal line (`--verbose`) with the time the previous one took: wall
// clock and the CPU time of every thread of the process (the GL driver's and the CPU
// references' included), which a busy machine does not inflate.
// "" ends the last stage.
void StepGrader::stage(const std::string& what) {
    const auto now = std::chrono::steady_clock::now();
    timespec cpu{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu);
    const double cpuMs = double(cpu.tv_sec) * 1e3 + double(cpu.tv_nsec) * 1e-6;
    if (!stageName_.empty())
        logLine(
            "grade",
            d_.id + ": " + stageName_ + " " +
                number(std::chrono::duration<double, std::milli>(now - stageStart_).count(), 4) +
                " ms (cpu " + number(cpuMs - stageCpuMs_, 4) + " ms)");
    stageName_ = what;
    stageStart_ = now;
    stageCpuMs_ = cpuMs;
    if (settings_.stage && !what.empty()) settings_.stage(d_.id + ": " + what);
}

}  // namespace pbrlab::step_grading

namespace pbrlab {

std::vector<std::string> exercisedValues(const ParamDecl& p) {
    std::vector<glm::dvec3> values;
    switch (p.type) {
        case ParamType::Int: {
            // Counts above the largest graded everywhere too (4096, 65536: graded at a few
            // points, kFewPointsAbove), so a function that stops using its count anywhere
            // above 1024 fails.
            const double lo = std::max(p.min, 1.0), hi = std::min(p.max, double(kFewPointsAbove));
            for (double v : {lo, 7.0, hi, 4096.0, 65536.0})
                if (v >= p.min && v <= p.max) values.push_back(glm::dvec3(v));
            break;
        }
        case ParamType::Float:
            values = {glm::dvec3(p.min), glm::dvec3(p.max)};
            break;
        case ParamType::Bool:
            values = {glm::dvec3(0), glm::dvec3(1)};
            break;
        case ParamType::Enum:
            for (size_t i = 0; i < p.choices.size(); ++i) values.push_back(glm::dvec3(double(i)));
            break;
        case ParamType::Color:
            values = {{0.9, 0.5, 0.1}, {0.1, 0.3, 0.8}};
            break;
        case ParamType::Direction:
            values = {glm::normalize(glm::dvec3(-5, 3, 6)), glm::normalize(glm::dvec3(2, -4, 7))};
            break;
    }
    std::vector<std::string> out;
    for (const glm::dvec3& v : values)
        if (v != p.defaultValue) out.push_back(p.name + "=" + p.format(v));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

std::vector<Surface> domainSurfaces(const ModuleDesc& module, std::uint64_t seed, int count) {
    std::vector<Surface> out;
    if (!module.domain) return out;
    DomainRandom random(seed);
    for (int i = 0; i < count; ++i) {
        Surface s = module.domain(random);
        s.covered = true;
        out.push_back(s);
    }
    return out;
}

StepResult gradeStep(LabRenderer& renderer, const LoadedModule& module, const DataPaths& paths,
                     const StudentSource& source, const GradeSettings& settings) {
    return step_grading::StepGrader(renderer, module, paths, source, settings).run();
}

nlohmann::json toJson(const CheckReport& c) {
    nlohmann::json j = {{"name", c.name},
                        {"kind", nameOf(c.kind)},
                        {"category", c.category ? nameOf(*c.category) : ""},
                        {"passed", c.passed},
                        {"deducted", c.deducted},
                        {"shows_work", c.showsWork},
                        {"detail", c.detail}};
    if (c.kind == CheckKind::Values || c.kind == CheckKind::Quality) {
        j["points"] = c.points;
        j["outside"] = c.outside;
        j["nan"] = c.nan;
        j["inf"] = c.inf;
        j["negative"] = c.negative;
        j["worst_excess"] = std::isfinite(c.worstExcess) ? c.worstExcess : 1e300;
        j["worst_at"] = c.worstAt;
        auto arr = [](const glm::dvec3& v) {
            auto f = [](double x) { return std::isfinite(x) ? x : 0.0; };
            return nlohmann::json::array({f(v.x), f(v.y), f(v.z)});
        };
        j["worst_value"] = arr(c.worstValue);
        j["worst_expected"] = arr(c.worstExpected);
        j["worst_accepted"] = {arr(c.worstLo), arr(c.worstHi)};
    } else if (c.kind == CheckKind::Robustness) {
        j["points"] = c.points;
        j["nan"] = c.nan;
        j["inf"] = c.inf;
        j["negative"] = c.negative;
        j["first_problem"] = c.worstAt;
    } else {
        j["measured"] = std::isfinite(c.measured) ? c.measured : 1e300;
        j["expected"] = c.expected;
    }
    return j;
}

}  // namespace pbrlab
