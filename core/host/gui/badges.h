// The steps' badges: each step's grade, as `pbrlab check ID --json` gives it, out of the
// window's way (a step takes up to seconds to grade; platform.h's StepGrades: a process of its
// own on the desktop, one at a time, the page's grader in a Web Worker), again whenever the
// student's file or a file it includes changes. The window polls it each frame and stays
// responsive.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "platform.h"
#include "source_watch.h"

namespace pbrlab {

class ModuleRegistry;

// NotGradedHere: a page whose browser cannot run the grader (a Web Worker with WebGL 2 on an
// OffscreenCanvas, docs/web.md); `pbrlab grade` gives the grade.
enum class Status { Unknown, Missing, CompileError, Passes, Fails, NotGradedHere };

struct Badge {
    Status status = Status::Unknown;
    std::string gradeMessage;  // why the badge says "fails": the grader's message
    SourceWatch watch;         // the student's file as last graded
    // markCompileError's: the file the window found does not compile (status is then of it).
    SourceWatch compileError;
};

class Badges {
public:
    // modulesDirs: the step folders the grading process loads, as this one does.
    Badges(std::vector<std::filesystem::path> modulesDirs, std::filesystem::path submission);
    Badges(const Badges&) = delete;
    Badges& operator=(const Badges&) = delete;
    ~Badges();  // a grade still running is not needed any more: it is stopped

    // Collects a finished grade, and starts the next one needed, step `first` (the one on
    // screen) before the others: at most one at a time on the desktop; in a page every one
    // needed, which the page's grader orders. Returns the id of a step whose grade just
    // arrived (empty: none).
    std::string update(const ModuleRegistry& registry, const std::string& first = {});

    // The step's badge (Status::Unknown before its first check).
    const Badge& of(const std::string& id) const {
        static const Badge unknown;
        auto it = badges_.find(id);
        return it == badges_.end() ? unknown : it->second;
    }
    // The step's badge is the grade of its file as it is on disk (or says it is missing).
    bool upToDate(const std::string& id) const;
    // The render found that the student's file does not compile: the badge says so now.
    void markCompileError(const std::string& id);

private:
    void start(const std::string& id);
    void markStale(const ModuleRegistry& registry);
    // No grade may start until the one running has finished (StepGrades::oneAtATime).
    bool waitsForAGrade() const;
    std::filesystem::path submission_;
    std::map<std::string, Badge> badges_;
    size_t cursor_ = 0;  // the step checked last, so every step gets its turn
    std::unique_ptr<platform::StepGrades> grades_;
    std::set<std::string> pending_;  // the steps being graded, whose report has not arrived
};

const char* badgeText(Status s);

}  // namespace pbrlab
