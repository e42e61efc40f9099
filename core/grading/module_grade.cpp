#include "grading/module_grade.h"

#include <cmath>

#include "shader/preprocess.h"
#include "steps/contract.h"

namespace pbrlab {

using json = nlohmann::json;

namespace {

std::string compileHints(const std::string& log) {
    std::string hints;
    std::vector<std::pair<std::string, const ContractStep*>> names;
    for (const ContractStep& s : contractSteps()) names.push_back({functionName(s.function), &s});
    for (const ContractHelper& h : contractHelpers())
        names.push_back({functionName(h.function), nullptr});
    for (const auto& [name, step] : names) {
        if (log.find("`" + name + "' redefined") == std::string::npos) continue;
        hints += "\nhint: " + name + " is a contract function that pbrlab provides" +
                 (step ? " (step " + std::to_string(step->step) + ", " + step->id + ")" : "") +
                 ": call it, or give your own helper another name.";
    }
    // Recursion and the host's own functions (main) are hinted where the log is traced back
    // to the student's line (mapCompilerLog), which knows whose function it is.
    return hints;
}

}  // namespace

ModuleGrade gradeModuleHere(LabRenderer& renderer, const LoadedModule& m, const DataPaths& paths,
                            const StudentSource& source, const GradeSettings& settings,
                            const std::function<void()>& afterGrading) {
    ModuleGrade g;
    g.id = m.desc->id;
    g.title = m.desc->title;
    try {
        const StepResult r = gradeStep(renderer, m, paths, source, settings);
        g.status = r.passed ? GradeStatus::Passed : GradeStatus::Failed;
        g.message = r.message;
        g.mistake = r.mistake;
        g.namedBy = r.namedBy;
        g.mistakeGroup = r.mistakeGroup;
        g.instructorNote = r.instructorNote;
        g.seconds = r.seconds;
        for (const CheckReport& c : r.checks) g.checks.push_back(toJson(c));
        if (afterGrading) afterGrading();
    } catch (const ShaderError& e) {
        g.status = GradeStatus::CompileError;
        g.message = e.what() + compileHints(e.what());
    } catch (const std::exception& e) {
        g.status = GradeStatus::Failed;
        g.message = e.what();
    }
    g.score = g.status == GradeStatus::Passed ? g.maxScore : 0;
    g.message = validUtf8(g.message);
    return g;
}

json gradeJson(const ModuleGrade& g) {
    return {{"id", g.id},
            {"title", g.title},
            {"status", g.status},
            {"score", roundPoints(g.score)},
            {"max_score", roundPoints(g.maxScore)},
            {"message", g.message},
            {"mistake", g.mistake},
            {"named_by", g.namedBy},
            {"mistake_group", g.mistakeGroup},
            {"checks", g.checks},
            {"instructor_note", g.instructorNote},
            {"seconds", g.seconds}};
}

ModuleGrade gradeFromJson(const json& j) {
    ModuleGrade g;
    g.id = j.value("id", "");
    g.title = j.value("title", "");
    g.status = j.at("status");
    g.score = j.value("score", 0.0);
    g.maxScore = j.value("max_score", 1.0);
    g.message = j.value("message", "");
    g.mistake = j.value("mistake", "");
    g.namedBy = j.value("named_by", NamedBy::Nothing);
    g.mistakeGroup = j.value("mistake_group", "");
    g.instructorNote = j.value("instructor_note", "");
    g.checks = j.value("checks", json::array());
    g.seconds = j.value("seconds", 0.0);
    return g;
}

std::int64_t toMicroPoints(double points) {
    return std::isfinite(points) ? std::llround(points * 1e6) : 0;
}

double fromMicroPoints(std::int64_t micro) {
    return double(micro) / 1e6;  // correctly rounded: the double nearest the decimal
}

double roundPoints(double points) {
    return fromMicroPoints(toMicroPoints(points));
}

std::string validUtf8(const std::string& text) {
    std::string out;
    const auto* p = reinterpret_cast<const unsigned char*>(text.data());
    const size_t n = text.size();
    for (size_t i = 0; i < n;) {
        const unsigned char c = p[i];
        int len = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
        bool ok = len > 0 && i + size_t(len) <= n;
        for (int k = 1; ok && k < len; ++k) ok = (p[i + size_t(k)] >> 6) == 2;
        if (ok && len == 2) ok = c >= 0xC2;  // no overlong forms
        if (ok && len == 3)
            ok = !(c == 0xE0 && p[i + 1] < 0xA0) && !(c == 0xED && p[i + 1] >= 0xA0);
        if (ok && len == 4)
            ok = c <= 0xF4 && !(c == 0xF0 && p[i + 1] < 0x90) && !(c == 0xF4 && p[i + 1] >= 0x90);
        if (ok && (c == 0 || (c < 0x20 && c != '\n' && c != '\t'))) ok = false;
        if (ok) {
            out.append(text, i, size_t(len));
            i += size_t(len);
        } else {
            out += "\xEF\xBF\xBD";  // U+FFFD
            ++i;
        }
    }
    return out;
}

}  // namespace pbrlab
