// The checks of gradeStep that are not values (step_grader.h): the contract (what a step may
// read), the module's invariants, the inputs the step's callers produce and the extreme-input
// sweep.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

#include "grading/error_patterns.h"
#include "grading/stability.h"
#include "grading/step_grader.h"
#include "shader/student_file.h"
#include "steps/contract.h"
#include "steps/plugin_host.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace pbrlab::step_grading {

namespace {

// The name of a contract function from its signature ("vec3 fresnelSchlick(float ..." ->
// "fresnelSchlick").
std::string functionName(const std::string& signature) {
    const size_t paren = signature.find('(');
    const std::string head = signature.substr(0, paren);
    const size_t space = head.find_last_of(' ');
    return space == std::string::npos ? head : head.substr(space + 1);
}

// A copy of a student's folder in which only `steps` are the student's: the other steps' files
// are left out, so a program built from it (cumulative) takes the reference solution for
// them. What a caller's program with the student's function inside is built from, and how a
// NaN is traced to the step that causes it. Every file is read through the one screening
// path (a file it refuses is left out); removed with the object.
class StepSubset {
public:
    StepSubset(const StudentSource& source, const std::vector<std::string>& steps) {
        dir_ = fs::temp_directory_path() /
               ("pbrlab-steps-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++));
        fs::create_directories(dir_);
        int files = 0;
        std::error_code ec;
        for (auto it = fs::recursive_directory_iterator(
                 source.dir, fs::directory_options::skip_permission_denied, ec);
             !ec && it != fs::recursive_directory_iterator() && files < 512;
             it.increment(ec), ++files) {
            // Lexically and without throwing: a student's folder may hold a link loop.
            const fs::path relative = it->path().lexically_relative(source.dir);
            if (it.depth() > 8) continue;
            std::error_code kind;
            if (it->is_directory(kind)) {
                fs::create_directories(dir_ / relative);
                continue;
            }
            if (it.depth() == 0 && it->path().extension() == ".glsl") {
                const std::string id = it->path().stem().string();
                const bool contractFile = findContractStep(id) != nullptr;
                if (contractFile && std::find(steps.begin(), steps.end(), id) == steps.end())
                    continue;
            }
            try {
                const std::string text = readStudentFile(it->path(), source.dir);
                std::ofstream(dir_ / relative, std::ios::binary) << text;
            } catch (const std::exception&) {
                // Refused: left out, as the student's program would refuse it.
            }
        }
    }
    ~StepSubset() {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    StepSubset(const StepSubset&) = delete;
    StepSubset& operator=(const StepSubset&) = delete;
    StudentSource source() const { return {dir_, true}; }

private:
    static int& counter() {
        static int n = 0;
        return n;
    }
    fs::path dir_;
};

// A view that calls the step's function, on the inputs it hands it.
struct Caller {
    std::string what;  // for the message
    const LoadedModule* module;
    ParamValues params;
    Scene scene;
};

// The step's callers: its own view, at each choice of its enum and bool parameters, and the
// view of every later step whose reference solution calls it, loaded into `registries`.
std::vector<Caller> callersOf(const LoadedModule& m, const DataPaths& paths, const Scene& scene,
                              std::vector<std::unique_ptr<ModuleRegistry>>& registries) {
    const ModuleDesc& d = *m.desc;
    const std::string function = functionName(d.function);
    std::vector<Caller> callers;
    callers.push_back({"this step's view", &m, ParamValues(d.params), scene});
    for (const ParamDecl& p : d.params) {
        if (p.type != ParamType::Enum && p.type != ParamType::Bool) continue;
        for (const std::string& a : exercisedValues(p))
            callers.push_back({"this step's view with " + a, &m, withSets(d, {a}), scene});
    }
    // Later steps whose reference solution calls this one, loaded from this step's module
    // folder (an out-of-tree caller elsewhere is not found and not graded here).
    for (const ContractStep& step : contractSteps()) {
        if (std::find(step.calls.begin(), step.calls.end(), d.id) == step.calls.end()) continue;
        try {
            registries.push_back(
                std::make_unique<ModuleRegistry>(m.library.parent_path(), step.id));
            const LoadedModule& caller = registries.back()->find(step.id);
            callers.push_back({"step " + std::to_string(step.step) + " " + step.id + " (" +
                                   functionName(step.function) + " calls your " + function + ")",
                               &caller, ParamValues(caller.desc->params),
                               loadScene(paths.scene(caller.desc->scene))});
        } catch (const std::exception&) {
        }
    }
    return callers;
}

// Whose code the callers' programs hold: the student's function (stepwise), or every step of
// the student's up to this one (cumulative); the reference solutions for the rest.
std::vector<std::string> studentSteps(const ModuleDesc& d, const StudentSource& source) {
    const ContractStep* self = findContractStep(d.id);
    std::vector<std::string> students{d.id};
    if (source.cumulative && self)
        for (const ContractStep& step : contractSteps())
            if (step.step < self->step) students.push_back(step.id);
    return students;
}

// NaN and Inf among a view's values on the callers' inputs, and the first such input.
struct Broken {
    int count = 0;
    std::string firstAt;
};

// The caller's view built with `source`, on `set`: its NaN and Inf.
Broken brokenValues(LabRenderer& renderer, const Caller& c, const StudentSource& source,
                    const ExtremeSet& set) {
    RenderRequest request{c.module,      &c.params, &c.scene,  source,
                          &set.surfaces, set.width, set.height};
    request.seamlessCubes = false;
    const Image value = renderer.render(request).value;
    Broken b;
    for (size_t i = 0; i < set.labels.size(); ++i)
        for (int k = 0; k < c.module->desc->components; ++k)
            if (!std::isfinite(value.pixels[i * 4 + size_t(k)])) {
                if (!b.count++) b.firstAt = set.labels[i];
                break;
            }
    return b;
}

// --cumulative: which of the student's steps makes the caller's NaN (their own function alone,
// else the first earlier step of theirs that does on its own), as the message adds it ("" when
// it is the graded step's or none alone).
std::string nanCulprit(LabRenderer& renderer, const Caller& c, const StudentSource& source,
                       const std::vector<std::string>& students, const ExtremeSet& set,
                       const std::string& graded) {
    std::string culprit;
    for (const std::string& id : students) {
        const StepSubset only(source, {id});
        Broken alone;
        try {
            alone = brokenValues(renderer, c, only.source(), set);
        } catch (const std::exception&) {
            continue;
        }
        if (alone.count) {
            culprit = id;
            break;
        }
    }
    if (culprit.empty() || culprit == graded) return "";
    const ContractStep* step = findContractStep(culprit);
    return "; it comes from your step " +
           (step ? std::to_string(step->step) + " " : std::string()) + culprit +
           (step ? " (" + functionName(step->function) + ")" : std::string()) +
           ", which gives NaN there on its own";
}

}  // namespace

// No step may read what its own or a later step's reference solution computed (the
// host precomputes those maps with the reference solutions).
void StepGrader::checkSamplers(const Program& program) {
    const std::vector<std::string> forbidden = LabRenderer::forbiddenSamplers(d_, program);
    CheckReport c;
    c.name = "reads only the inputs this step may read";
    c.kind = CheckKind::Contract;
    c.category = CheckCategory::Contract;
    c.passed = forbidden.empty();
    if (forbidden.empty()) {
        c.detail = "no map computed by this step's or a later step's reference solution";
    } else {
        for (const std::string& f : forbidden) {
            const ContractStep* step = findProvider(f);
            c.detail += (c.detail.empty() ? "" : "; ") + f +
                        (step ? " is computed by the reference solution of step " +
                                    std::to_string(step->step) + " (" + step->id + ")"
                              : " is not an input of this step");
        }
        c.detail +=
            ": your function may not read it here (it reads black); compute the "
            "value from uEnvironment instead";
    }
    record(c);
}

// A loop that never ends, found before the other checks: each of them would be the guard's NaN
// at the cost of the whole budget per point (a minute and more of a grade where the budget is
// the most llvmpipe runs), and none would say more. 64 points of the probe at the default
// parameters, drawn as the values checks draw them; where one is NaN, the diagnosis build says
// whether the guard cut a loop there. A failed contract check: the function does not return,
// which the contract asks of it (a loop the preprocessor reads as endless is a compile error),
// and no partial credit is given. Recorded only when a loop was cut, so that the checks of every
// other grade are what they were.
void StepGrader::checkLoopsEnd(const Scene& scene, const Program& program) {
    if (program.loops().empty() || source_.dir.empty()) return;
    stage("every loop ends");
    const std::vector<Surface> all = probeSurfaces(d_.probe);
    std::vector<Surface> points;
    const size_t count = std::min<size_t>(all.size(), 64);
    for (size_t k = 0; k < count; ++k) points.push_back(all[k * all.size() / count]);
    const Grid g = grid(points);
    const ParamValues params(d_.params);
    auto render = [&](bool diagnosis) {
        StudentSource source = source_;
        source.traceNonFinite = diagnosis;
        RenderRequest request{&m_, &params, &scene, source, &g.surfaces, g.width, g.height};
        request.seamlessCubes = false;
        request.isolatePoints = true;
        return renderer_.render(request);
    };
    const std::vector<glm::dvec3> values = pointValues(render(false).value, count);
    if (std::none_of(values.begin(), values.end(),
                     [](const glm::dvec3& v) { return std::isnan(v.x + v.y + v.z); }))
        return;
    RenderResult traced;
    try {
        traced = render(true);
    } catch (const Error&) {
        return;  // the diagnosis build does not compile: the other checks judge
    }
    std::map<size_t, int> cuts;  // loop K (written as -K) -> points
    for (const glm::dvec3& c : pointValues(traced.value, count))
        if (c.z < -0.5 && -c.z <= double(traced.loops.size())) ++cuts[size_t(std::lround(-c.z))];
    if (cuts.empty()) return;
    size_t loop = cuts.begin()->first;
    int cut = 0;
    for (const auto& [k, n] : cuts) {
        if (n > cuts[loop]) loop = k;
        cut += n;
    }
    CheckReport c;
    c.name = "every loop of your files ends";
    c.kind = CheckKind::Contract;
    c.category = CheckCategory::Contract;
    c.passed = false;
    c.detail = loopCutMessage(traced.loops[loop - 1], traced.loopBudget, cut, int(count));
    loopCut_ = c.detail;
    record(c);
    throw Stopped{};
}

void StepGrader::gradeInvariants(const Scene& scene) {
    if (!d_.invariants) return;
    stage("invariants");
    Evaluator evaluator;
    evaluator.run = [&](const std::vector<Surface>& surfaces, const std::string& view,
                        const std::vector<std::string>& set) {
        // Rows of kRowWidth points; a copy only when the last row needs padding (the
        // chi-square test's 131072 samples do not).
        const bool whole = !surfaces.empty() && surfaces.size() % kRowWidth == 0;
        const Grid g = whole ? Grid() : grid(surfaces);
        const ParamValues params = withSets(d_, set);
        RenderRequest request{&m_,
                              &params,
                              &scene,
                              source_,
                              whole ? &surfaces : &g.surfaces,
                              kRowWidth,
                              whole ? int(surfaces.size() / kRowWidth) : g.height};
        request.seamlessCubes = false;
        request.isolatePoints = true;
        request.view = view;
        return pointValues(renderer_.render(request).value, surfaces.size());
    };
    for (const InvariantResult& inv : d_.invariants(evaluator)) {
        CheckReport c;
        c.name = inv.name;
        c.kind = CheckKind::Invariant;
        c.category = CheckCategory::Invariants;
        c.measured = inv.measured;
        c.expected = inv.expected;
        c.passed = inv.holds;
        c.detail = inv.name + " = " + number(inv.measured) + ", expected " + inv.expected;
        if (!inv.holds && !inv.hint.empty()) c.detail += " (" + inv.hint + ")";
        record(c);
    }
}

// The step's function on what its callers hand it (docs/grading.md, "Every input the contract
// gives, graded over its range"). The callers are the step's own view, at each choice of its
// enum and bool parameters (fresnel's view feeds N.V or H.V), and the view of every later step
// whose reference solution calls it (specular feeds fresnelSchlick max(dot(H, V), 0.0), 1 + 1
// ulp when V = L), each built with the student's function and the reference solutions around
// it, on callerSurfaces with the smallest roughness that view passes. NaN or Inf there fails
// the step. Estimators (17-20) are graded by convergence, their values finite at every count.
// Its cost is mostly compiling the callers' programs, so a step with many callers (f0,
// fresnel) pays the most; `pbrlab -v check ID` prints it as "inputs its callers produce".
void StepGrader::gradeCallerInputs(const Scene& scene) {
    if (d_.estimator) return;
    stage("inputs its callers produce");
    std::vector<std::unique_ptr<ModuleRegistry>> registries;
    const std::vector<Caller> callers = callersOf(m_, paths_, scene, registries);
    const std::vector<std::string> students = studentSteps(d_, source_);
    std::unique_ptr<StepSubset> subset;
    if (!source_.dir.empty()) subset = std::make_unique<StepSubset>(source_, students);

    CheckReport r;
    r.name = "inputs its callers produce";
    r.kind = CheckKind::Invariant;
    r.category = CheckCategory::Invariants;
    r.expected = "0 NaN or Inf";
    int points = 0, views = 0;
    std::string skipped;
    for (const Caller& c : callers) {
        const ExtremeSet set = callerSurfaces(smallestRoughness(*c.module->desc));
        const bool own = c.module == &m_;
        const StudentSource source = own || !subset ? source_ : subset->source();
        Broken b;
        try {
            b = brokenValues(renderer_, c, source, set);
        } catch (const std::exception&) {
            // A caller's program that does not build with the student's file alone (it
            // includes another step's file): not graded here; the student's own program built.
            skipped += (skipped.empty() ? "" : ", ") + c.what;
            continue;
        }
        points += int(set.labels.size());
        ++views;
        if (!b.count) continue;
        r.passed = false;
        r.measured = b.count;
        r.worstAt = b.firstAt;
        r.detail = "NaN on an input its callers produce: " + c.what + " gives NaN or Inf at " +
                   std::to_string(b.count) + " of " + std::to_string(set.labels.size()) +
                   " inputs, first at " + b.firstAt;
        if (source_.cumulative && !source_.dir.empty())
            r.detail += nanCulprit(renderer_, c, source_, students, set, d_.id);
        break;
    }
    if (r.passed)
        r.detail = std::to_string(points) + " inputs in " + std::to_string(views) +
                   " views (this step's and its callers'): no NaN or Inf";
    if (!skipped.empty()) r.detail += "; not run (does not build with your file alone): " + skipped;
    record(r);
}

void StepGrader::gradeRobustness(const Scene& scene) {
    stage("robustness");
    const StabilityResult st = stabilitySweep(renderer_, m_, scene, source_);
    CheckReport c;
    c.name = "robustness on extreme inputs";
    c.kind = CheckKind::Robustness;
    c.category = CheckCategory::Robustness;
    c.deducted = false;
    c.points = st.gpu.compared;
    c.nan = st.gpu.nanCount;
    c.inf = st.gpu.infCount;
    c.negative = d_.nonNegative ? st.gpu.negativeCount : 0;
    c.passed = c.nan + c.inf + c.negative == 0;
    c.worstAt = st.firstProblem;
    c.detail = std::to_string(c.points) + " extreme inputs: " + std::to_string(c.nan) + " NaN, " +
               std::to_string(c.inf) + " Inf, " + std::to_string(c.negative) + " negative" +
               (st.firstProblem.empty() ? "" : "; first at " + st.firstProblem);
    record(c);
}

}  // namespace pbrlab::step_grading
