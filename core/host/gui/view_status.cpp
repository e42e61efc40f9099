#include "view_status.h"

#include <cctype>
#include <cstdio>

#include "lab.h"

namespace pbrlab {

namespace {

ViewStatus::Row statsRow(const char* who, const Comparison& s, const ModuleDesc& d) {
    const bool ok = s.passes(d.nonNegative, d.tolerance.outlierFraction);
    char text[256];
    std::snprintf(text, sizeof text,
                  "%-9s worst %.3g x the tolerance  outside %d  NaN %d  Inf %d  neg %d  %s", who,
                  s.worstExcess, s.outside, s.nanCount, s.infCount, s.negativeCount,
                  ok ? "within the band" : "outside the band");
    return {text, ok};
}

}  // namespace

ViewStatus viewStatus(const Lab& lab, const GuiState& state) {
    const ModuleDesc& d = lab.module(state);
    const Shown& shown = lab.shown();
    const std::string file = d.id + ".glsl";
    // The picture and the statistics are of the last program that compiled, not of the file.
    const bool lastGood =
        !shown.compileLog.empty() && !shown.refused && !shown.studentValue.pixels.empty();
    ViewStatus s;
    s.lastGood = lastGood;
    if (shown.refused) {
        s.error = file + " cannot be used, so the picture is the solution's:";
        s.errorLog = shown.compileLog;
    } else if (!shown.compileLog.empty()) {
        s.error = lastGood ? file +
                                 " does not compile: the picture and the statistics are of "
                                 "the last program that compiled, " +
                                 shown.compiledAt
                           : file +
                                 " does not compile, and no version of it has yet: the "
                                 "picture is the solution's";
        s.errorLog = shown.compileLog;
    } else if (shown.studentValue.pixels.empty() && showsStudent(state.view)) {
        s.notice = shown.hasStudent ? "your file has not compiled yet: showing the solution"
                                    : "no student file for this step: showing the solution";
    }
    if (lab.evaluating()) {  // on the evaluation thread: the window draws on meanwhile
        const EvaluationProgress p = lab.evaluationProgress();
        char text[256];
        if (p.running)
            std::snprintf(text, sizeof text,
                          "vs the CPU reference: evaluating %s (%d of %d), %.1f s", p.what.c_str(),
                          p.stage, p.stages, p.seconds);
        else
            std::snprintf(text, sizeof text, "vs the CPU reference: evaluating");
        s.statsHeading = text;
        return s;
    }
    if (shown.liveTexture || shown.liveWaitsForMaps) {
        s.statsHeading = "vs the CPU reference: follows when the input stops";
        return s;
    }
    s.statsHeading =
        lastGood ? "showing the last program that compiled, " + shown.compiledAt +
                       " (not the file on disk), vs the CPU reference's band on this picture:"
                 : "vs the CPU reference's band on this picture (the badge is the grade):";
    if (!shown.studentValue.pixels.empty())
        s.rows.push_back(statsRow(lastGood ? "last good" : "student", shown.studentStats, d));
    if (shown.solutionWithheld)
        s.rows.push_back({"solution  not in this site: views show the CPU reference", true});
    else
        s.rows.push_back(statsRow("solution", shown.solutionStats, d));
    // The reference solution outside its own band: this GPU computes the picture otherwise
    // than the CPU reference expects (a browser's SwiftShader moves an estimator's samples
    // with its approximate sin, cos and pow: docs/web.md). The band judges nothing here.
    if (!shown.solutionWithheld && !s.rows.back().ok)
        s.bandNote =
            std::string("the solution's own picture is outside the band on this GPU, so ") +
            "these rows cannot judge yours here: the badge is the grade" +
            (d.estimator ? " (it compares estimates with the converged integral)" : "");
    const Badge& badge = lab.badges().of(d.id);
    if (badge.status == Status::CompileError && lastGood)
        s.grade = "badge: compile error, the grade of " + file +
                  " on disk; the rows above are the last program that compiled, " +
                  shown.compiledAt;
    else if (badge.status == Status::Fails && !badge.gradeMessage.empty()) {
        auto [first, rest] = firstSentence(badge.gradeMessage);
        s.grade = "grade: " + first;
        s.gradeDetails = rest;
    } else if (badge.status == Status::NotGradedHere)
        s.grade =
            "badge: this browser cannot grade (no WebGL 2 in a worker); the rows above are the "
            "check against the CPU reference, and `pbrlab grade` on the kit gives the grade";
    return s;
}

std::pair<std::string, std::string> firstSentence(const std::string& message) {
    for (size_t i = 1; i + 2 < message.size(); ++i) {
        const char c = message[i];
        if ((c == '.' || c == '?' || c == '!') && message[i - 1] != '.' && message[i + 1] == ' ' &&
            std::isupper(static_cast<unsigned char>(message[i + 2])))
            return {message.substr(0, i + 1), message.substr(i + 2)};
    }
    return {message, ""};
}

std::string describe(const ViewStatus& status) {
    std::string text;
    auto line = [&](const std::string& l) {
        if (!l.empty()) text += l + "\n";
    };
    line(status.error);
    size_t start = 0;
    while (start < status.errorLog.size()) {
        size_t end = status.errorLog.find('\n', start);
        if (end == std::string::npos) end = status.errorLog.size();
        line("  " + status.errorLog.substr(start, end - start));
        start = end + 1;
    }
    line(status.notice);
    line(status.statsHeading);
    for (const ViewStatus::Row& row : status.rows) line(row.text);
    line(status.bandNote);
    line(status.grade);
    line(status.gradeDetails);
    return text;
}

}  // namespace pbrlab
