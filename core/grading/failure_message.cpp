// Why a step failed (step_grader.h): the message from the first failed check, and the mistake
// named from the error of the worst: patterns, the step's typical mistakes, mutants.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "grading/error_patterns.h"
#include "grading/mutants_mechanical.h"
#include "grading/step_grader.h"
#include "shader/student_file.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace pbrlab::step_grading {

namespace {

std::string vec(const glm::dvec3& v, int components) {
    std::string s = "(";
    for (int c = 0; c < components; ++c) s += (c ? ", " : "") + number(v[c]);
    return components == 1 ? number(v.x) : s + ")";
}

// The name of a typical mistake: its file's leading comment block, one sentence. The line
// `// expect: WORDS` is the test's (what the message must contain): never part of the name,
// or the message would contain the words because the file says them.
std::string mistakeName(const fs::path& file) {
    std::ifstream in(file);
    std::string name;
    for (std::string line; std::getline(in, line) && line.rfind("//", 0) == 0;) {
        if (line.rfind("// expect:", 0) == 0) continue;
        line = line.substr(2);
        if (name.empty() && line.rfind(" mistake:", 0) == 0) line = line.substr(9);
        const size_t b = line.find_first_not_of(' ');
        if (b != std::string::npos) name += (name.empty() ? "" : " ") + line.substr(b);
    }
    if (name.empty()) name = file.stem().string();
    if (name.back() != '.') name += '.';
    return name;
}

// What leads the message: a broken contract (it reads what it may not) explains
// everything after it; else the values check with its worst input; else the first failed.
const CheckReport* leadingCheck(const std::vector<CheckReport>& checks) {
    const CheckReport* first = nullptr;
    for (const std::optional<CheckKind> kind :
         {std::optional(CheckKind::Contract), std::optional(CheckKind::Values),
          std::optional<CheckKind>()})
        for (const CheckReport& c : checks)
            if (!first && c.deducted && !c.passed && (!kind || c.kind == *kind)) first = &c;
    return first;
}

// What the leading check says, with its worst input when it compares values ("" without one).
std::string leadingMessage(const CheckReport* first, int components) {
    std::string message;
    if (first) {
        message = first->name + ": " + first->detail;
        if (first->kind == CheckKind::Values && !first->worstAt.empty())
            message += "; at " + first->worstAt + ": yours " + vec(first->worstValue, components) +
                       ", expected " + vec(first->worstExpected, components) + " (accepted " +
                       vec(first->worstLo, components) + " .. " + vec(first->worstHi, components) +
                       ")";
    }
    return message;
}

// A loop the guard cut (written as -K, view_main.frag): the one most points name.
void noteCutLoop(const std::vector<glm::dvec3>& calls, const RenderResult& diagnosis,
                 FeedbackInputs::NonFiniteOrigin& origin) {
    std::map<size_t, int> cuts;
    for (const glm::dvec3& c : calls)
        if (c.z < -0.5 && -c.z <= double(diagnosis.loops.size())) ++cuts[size_t(std::lround(-c.z))];
    for (const auto& [k, points] : cuts)
        if (points > origin.cutPoints) {
            origin.cut = diagnosis.loops[k - 1];
            origin.cutPoints = points;
            origin.loopBudget = diagnosis.loopBudget;
        }
}

// The site most points share, among those where it is the cause (the value finite
// with what the traced calls made replaced), else among all.
void noteSharedSite(const std::vector<glm::dvec3>& calls, FeedbackInputs::NonFiniteOrigin& origin) {
    std::map<std::pair<int, int>, int> confirmed, noted;
    std::map<std::pair<int, int>, TraceSite> other;
    for (const glm::dvec3& c : calls) {
        const TraceSite site = traceSite(c.x);
        if (!site.traced()) continue;
        const std::pair<int, int> key{site.call, site.line};
        ++(c.z > 0.5 ? confirmed : noted)[key];
        if (traceSite(c.y).traced()) other[key] = traceSite(c.y);
    }
    origin.traced = int(calls.size());
    origin.confirmed = !confirmed.empty();
    for (const auto& [key, points] : confirmed.empty() ? noted : confirmed)
        if (points > origin.points) {
            origin.site = {key.first, key.second};
            origin.other = other.count(key) ? other[key] : TraceSite{};
            origin.points = points;
        }
}

// Whether every value is the same (within 1e-7): a constant output says all there is to say.
bool constantValues(const std::vector<glm::dvec3>& values) {
    bool constant = !values.empty();
    for (const glm::dvec3& v : values)
        constant = constant &&
                   glm::all(glm::lessThanEqual(glm::abs(v - values.front()), glm::dvec3(1e-7)));
    return constant;
}

}  // namespace

// What the typical mistakes and the mutants are compared with: up to 96 points of the failed
// check (its worst, up to 48 where the student's value is outside the band, the rest evenly
// spread) and the student's values there, rendered once. Every candidate is then one small
// render on the same points.
struct StepGrader::Sample {
    std::vector<size_t> picked;  // indices into the failed check's points
    std::vector<bool> wrong;     // the student's value outside the band there
    int wrongCount = 0;
    std::vector<Surface> points;  // those points, in rows of kRowWidth (padded)
    int height = 0;
    Image student;
};

// At how many of the sampled points a candidate's values equal the student's (within twice
// the band's width), and how far apart they are over all of them (0: equal everywhere).
struct StepGrader::Agreement {
    int same = 0, sameWhereWrong = 0;
    double distance = 0;
    // Equal at 95% of the sampled points and at 90% of those where the student's value is
    // wrong: a candidate that is right where the student is right, and nothing more, names
    // nothing (an error at 65 of 8385 points is one or two points of an even sample).
    bool matches(const Sample& sample) const {
        return same >= 0.95 * double(sample.picked.size()) &&
               sameWhereWrong >= 0.9 * double(sample.wrongCount);
    }
};

// Each mutant of the reference solution (grading/mutants_mechanical.h) on the sampled points: one
// the student's values equal (at 95% of them, the closest overall) is the mistake, said to the
// student by its family; its change quotes the reference and goes to the instructor only. One equal
// everywhere cannot be beaten: the search stops there.
struct StepGrader::MutantMatch {
    std::string mistake;  // for the student
    std::string change;   // for the instructor: `mutated` for `reference`
};

// The failure message: the first failed check, and the mistake named from the shape of
// the error of the check that failed worst.
void StepGrader::explain() {
    if (!loopCut_.empty()) {  // the grade stopped there: the loop is all there is to say
        result_.message = result_.mistake = loopCut_;
        result_.namedBy = NamedBy::Pattern;
        result_.mistakeGroup = withoutFigures(loopCut_);
        return;
    }
    const CheckReport* first = leadingCheck(result_.checks);
    std::string message = leadingMessage(first, d_.components);
    if (failed_ && failed_->cause.empty() && failed_->fromScene && settings_.feedback)
        failed_->cause = derivativesCauseOf(*failed_);
    if (failed_ && !failed_->cause.empty()) {
        // The check that failed found the cause itself (a sun's light dropped, screen-space
        // derivatives): the patterns below compare points drawn alone on other inputs, where
        // such a function is right, and would name something else.
        result_.mistake = failed_->cause;
        result_.namedBy = NamedBy::Pattern;
        result_.mistakeGroup = withoutFigures(failed_->cause);
    } else if (failed_ && settings_.feedback) {
        nameMistake(*failed_);
    }
    for (const CheckReport& c : result_.checks)
        if (c.deducted && !c.passed && c.kind != CheckKind::Values && &c != first)
            message += "; " + c.name + ": " + c.detail;
    if (!result_.mistake.empty() && message.find(result_.mistake) != std::string::npos)
        result_.message = message;  // the failed check's own words name it already
    else
        result_.message = result_.mistake.empty() || (first && first->kind == CheckKind::Contract)
                              ? message + (result_.mistake.empty() ? "" : " " + result_.mistake)
                              : result_.mistake + " " + message;
}

// The mistake named from the failed run's error: the patterns first, then the step's typical
// mistakes and the mutants of the reference where the patterns leave it open.
void StepGrader::nameMistake(const ValuesRun& f) {
    stage("feedback");
    const FeedbackInputs in = feedbackInputs(f);
    bool exact = false;
    result_.mistake = classifyError(in, &exact);
    if (!result_.mistake.empty()) result_.namedBy = NamedBy::Pattern;
    result_.mistakeGroup = withoutFigures(result_.mistake);
    // A constant output says all there is to say: a typical mistake that is 0 where the
    // reference is not (-L under a clamp) would "match" it on the failed points only.
    const bool constant = constantValues(in.values);
    const bool lookFurther = !(exact && constant);
    // The candidates below are compared on a sample of the failed check's points.
    Sample points;
    if (lookFurther && (settings_.typicalMistakes || settings_.mutantCatalogue)) points = sample(f);
    const std::string typical =
        lookFurther && settings_.typicalMistakes ? typicalMistake(f, points) : "";
    if (!typical.empty()) {
        result_.mistake += (result_.mistake.empty() ? "" : " ") +
                           std::string("It matches a typical mistake: ") + typical;
        if (!exact) result_.namedBy = NamedBy::Typical;
        result_.mistakeGroup = typical;
    }
    // When no pattern accounts for every point, the mutants of the reference solution:
    // the one change the student's values equal.
    if (lookFurther && !exact && typical.empty() && settings_.mutantCatalogue) {
        stage("feedback: one change from the reference");
        const MutantMatch match = mutantMatch(f, points);
        if (!match.mistake.empty()) {
            result_.mistake += (result_.mistake.empty() ? "" : " ") + match.mistake;
            result_.namedBy = NamedBy::Mutant;
            result_.mistakeGroup = match.mistake;
            result_.instructorNote = "the reference with " + match.change;
        }
    }
}

// What the error patterns read of the failed run: its covered points with the student's
// values and the band, and the student's function and the reference on other inputs.
FeedbackInputs StepGrader::feedbackInputs(const ValuesRun& f) {
    FeedbackInputs in;
    in.module = &d_;
    for (size_t i = 0; i < f.surfaces.size(); ++i) {
        if (!f.surfaces[i].covered) continue;
        in.surfaces.push_back(f.surfaces[i]);
        in.values.emplace_back(f.value.pixels[i * 4], f.value.pixels[i * 4 + 1],
                               f.value.pixels[i * 4 + 2]);
        in.expected.push_back(f.band.expected[i]);
        in.slack.push_back(f.band.slack[i]);
    }
    const Scene bound = applyParamBindings(f.scene, d_, f.params);
    auto context = std::make_shared<ReferenceContext>(
        referenceContext(renderer_, d_, bound, f.params, kGradingIbl));
    in.reference = [this, context](const Surface& s) { return d_.reference(s, *context); };
    in.context = context.get();
    in.student = [this, &f](const std::vector<Surface>& surfaces) {
        const Grid g = grid(surfaces);
        RenderRequest request{&m_, &f.params, &f.scene, source_, &g.surfaces, g.width, g.height};
        request.seamlessCubes = false;
        request.isolatePoints = true;
        return pointValues(renderer_.render(request).value, surfaces.size());
    };
    in.traceNonFinite = [this, &f](const std::vector<Surface>& surfaces) {
        return nonFiniteOrigin(f, surfaces);
    };
    // The estimator's bands are not the reference's: the sensitivity test would
    // compare against the same-sample reference, so it is left out there.
    if (!d_.estimator) in.domain = d_.domain;
    if (!source_.dir.empty()) {
        try {
            const fs::path file = source_.dir / (d_.id + ".glsl");
            in.studentCode = readStudentFile(file, source_.dir);
        } catch (const Error&) {
            // No file of the student's here (the reference is graded): nothing to read.
        }
    }
    return in;
}

// The points where the value is not finite, again, with the diagnosis build: which
// of the student's calls made the first NaN or Inf there.
FeedbackInputs::NonFiniteOrigin StepGrader::nonFiniteOrigin(const ValuesRun& f,
                                                            const std::vector<Surface>& surfaces) {
    FeedbackInputs::NonFiniteOrigin origin;
    if (source_.dir.empty()) return origin;  // the reference solutions: no one to tell
    StudentSource traced = source_;
    traced.traceNonFinite = true;
    const Grid g = grid(surfaces);
    RenderRequest request{&m_, &f.params, &f.scene, traced, &g.surfaces, g.width, g.height};
    request.seamlessCubes = false;
    request.isolatePoints = true;
    std::vector<glm::dvec3> calls;
    RenderResult diagnosis;
    try {
        diagnosis = renderer_.render(request);
        calls = pointValues(diagnosis.value, surfaces.size());
    } catch (const Error&) {
        return origin;  // the diagnosis build does not compile: nothing to say
    }
    noteCutLoop(calls, diagnosis, origin);
    noteSharedSite(calls, origin);
    return origin;
}

StepGrader::Sample StepGrader::sample(const ValuesRun& f) {
    Sample out;
    std::vector<size_t> covered;
    for (size_t i = 0; i < f.surfaces.size(); ++i)
        if (f.surfaces[i].covered) covered.push_back(i);
    if (covered.empty()) return out;
    // Up to 48 of the points where the student's value is outside the band (the worst
    // first), the rest spread over all: 96 in all.
    auto outside = [&](size_t i) {
        const glm::dvec3 v(f.value.pixels[i * 4], f.value.pixels[i * 4 + 1],
                           f.value.pixels[i * 4 + 2]);
        for (int c = 0; c < d_.components; ++c)
            if (!(std::abs(v[c] - f.band.expected[i][c]) <= f.band.slack[i][c])) return true;
        return false;
    };
    std::vector<size_t> wrong;
    for (size_t i : covered)
        if (outside(i)) wrong.push_back(i);
    if (f.worstIndex >= 0 && f.surfaces[size_t(f.worstIndex)].covered)
        out.picked.push_back(size_t(f.worstIndex));
    const size_t fromWrong = std::min<size_t>(wrong.size(), 48);
    for (size_t k = 0; k < fromWrong; ++k) {
        const size_t i = wrong[k * wrong.size() / fromWrong];
        if (std::find(out.picked.begin(), out.picked.end(), i) == out.picked.end())
            out.picked.push_back(i);
    }
    const size_t step = std::max<size_t>(1, covered.size() / (96 - out.picked.size()));
    for (size_t k = 0; k < covered.size() && out.picked.size() < 96; k += step)
        if (std::find(out.picked.begin(), out.picked.end(), covered[k]) == out.picked.end())
            out.picked.push_back(covered[k]);
    for (size_t i : out.picked) {
        out.wrong.push_back(outside(i));
        out.wrongCount += out.wrong.back();
    }
    for (size_t i : out.picked) out.points.push_back(f.surfaces[i]);
    out.points.resize((out.points.size() + kRowWidth - 1) / kRowWidth * kRowWidth);
    out.height = int(out.points.size() / kRowWidth);
    out.student = valuesOn(f, out, source_);
    return out;
}

Image StepGrader::valuesOn(const ValuesRun& f, const Sample& sample, const StudentSource& source) {
    RenderRequest request{&m_,       &f.params,    &f.scene, source, &sample.points,
                          kRowWidth, sample.height};
    request.seamlessCubes = false;
    request.isolatePoints = true;
    return renderer_.render(request).value;
}

StepGrader::Agreement StepGrader::agreement(const ValuesRun& f, const Sample& sample,
                                            const Image& candidate) const {
    Agreement a;
    for (size_t p = 0; p < sample.picked.size(); ++p) {
        bool equal = true;
        for (int c = 0; c < d_.components; ++c) {
            const double v = sample.student.pixels[p * 4 + size_t(c)],
                         m = candidate.pixels[p * 4 + size_t(c)];
            const double slack = 2 * f.band.slack[sample.picked[p]][c] + 1e-6 * std::abs(m);
            const double e = v == m ? 0 : std::abs(v - m) / std::max(slack, 1e-300);
            equal = equal && e <= 1;
            a.distance += std::isfinite(e) ? std::min(e, 1e6) : 1e6;
        }
        a.same += equal;
        a.sameWhereWrong += equal && sample.wrong[p];
    }
    return a;
}

// The step's typical mistakes (labs/<id>/mistakes/*.glsl): the one the student's values
// equal at 95% of the sampled points names the mistake outright.
std::string StepGrader::typicalMistake(const ValuesRun& f, const Sample& sample) {
    const fs::path dir = m_.sourceDir / "mistakes";
    std::error_code ec;
    if (sample.picked.empty() || !fs::is_directory(dir, ec)) return "";
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.path().extension() == ".glsl") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    const fs::path tmp =
        fs::temp_directory_path() / ("pbrlab-mistake-" + std::to_string(::getpid()));
    std::string best;
    double bestShare = 0.95;
    for (const fs::path& file : files) {
        fs::create_directories(tmp, ec);
        fs::copy_file(file, tmp / (d_.id + ".glsl"), fs::copy_options::overwrite_existing, ec);
        try {
            const Agreement a = agreement(f, sample, valuesOn(f, sample, {tmp, false}));
            const double share = double(a.same) / double(sample.picked.size());
            if (a.matches(sample) && share >= bestShare)
                bestShare = share, best = mistakeName(file);
        } catch (const Error&) {
        }
    }
    fs::remove_all(tmp, ec);
    return best;
}

StepGrader::MutantMatch StepGrader::mutantMatch(const ValuesRun& f, const Sample& sample) {
    if (sample.picked.empty()) return {};
    std::ifstream in(m_.sourceDir / "solution.glsl", std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    const std::vector<Mutant> mutants = generateMutants(text.str());
    const fs::path tmp =
        fs::temp_directory_path() / ("pbrlab-feedback-" + std::to_string(::getpid()));
    std::error_code ec;
    fs::create_directories(tmp, ec);
    MutantMatch best;
    double bestDistance = 1e300;
    for (size_t k = 0; k < mutants.size() && bestDistance > 0; ++k) {
        const fs::path dir = tmp / std::to_string(k);
        fs::create_directories(dir, ec);
        std::ofstream(dir / (d_.id + ".glsl"), std::ios::binary) << mutants[k].text;
        Image mutant;
        try {
            mutant = valuesOn(f, sample, {dir, false});
        } catch (const Error&) {
            continue;  // does not compile
        }
        const Agreement a = agreement(f, sample, mutant);
        if (a.matches(sample) && a.distance < bestDistance) {
            bestDistance = a.distance;
            std::string mistake = mutants[k].family;
            for (const MutantFamily& family : mutantFamilies())
                if (mutants[k].family == family.name) mistake = family.mistake;
            best = {"It behaves like the reference with one change: " + mistake + ".",
                    mutants[k].change};
        }
    }
    fs::remove_all(tmp, ec);
    return best;
}

}  // namespace pbrlab::step_grading
