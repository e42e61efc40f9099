#include "badges.h"

#include <nlohmann/json.hpp>

#include "grading/module_grade.h"
#include "steps/plugin_host.h"

namespace fs = std::filesystem;

namespace pbrlab {

const char* badgeText(Status s) {
    switch (s) {
        case Status::Missing:
            return "missing";
        case Status::CompileError:
            return "compile error";
        case Status::Passes:
            return "passes";
        case Status::Fails:
            return "fails";
        case Status::NotGradedHere:
            return "ungraded";  // in a page (view_status.cpp says why)
        default:
            return "...";
    }
}

namespace {

// The badge of a grade report, as `pbrlab check --json` writes it (empty: it never came).
void takeReport(Badge& badge, const std::string& text) {
    try {
        const nlohmann::json report = nlohmann::json::parse(text);
        const ModuleGrade g = gradeFromJson(report.at("modules").at(0));
        badge.status = g.status == GradeStatus::Passed         ? Status::Passes
                       : g.status == GradeStatus::CompileError ? Status::CompileError
                                                               : Status::Fails;
        badge.gradeMessage = g.message;
    } catch (const std::exception&) {
        badge.status = Status::Fails;
        badge.gradeMessage = "the grade did not finish";
    }
}

}  // namespace

Badges::Badges(std::vector<std::filesystem::path> modulesDirs, std::filesystem::path submission)
    : submission_(submission), grades_(platform::stepGrades(std::move(modulesDirs), submission)) {}

Badges::~Badges() = default;

std::string Badges::update(const ModuleRegistry& registry, const std::string& first) {
    std::string arrived;
    for (auto it = pending_.begin(); it != pending_.end();) {
        const std::optional<std::string> report = grades_->report(*it);
        if (!report) {
            ++it;
            continue;
        }
        takeReport(badges_[*it], *report);
        arrived = *it;
        it = pending_.erase(it);
    }
    if (waitsForAGrade()) {
        markStale(registry);
        return arrived;
    }
    const auto& ms = registry.modules();
    // The step on screen first, then the others from the one after the last started.
    std::vector<size_t> order;
    for (size_t k = 0; k < ms.size(); ++k)
        if (ms[k].desc->id == first) order.push_back(k);
    for (size_t k = 1; k <= ms.size(); ++k)
        if (ms[(cursor_ + k) % ms.size()].desc->id != first)
            order.push_back((cursor_ + k) % ms.size());
    for (const size_t k : order) {
        const std::string& id = ms[k].desc->id;
        Badge& badge = badges_[id];
        fs::path file = submission_.empty() ? fs::path() : submission_ / (id + ".glsl");
        if (file.empty() || !fs::exists(file)) {
            badge.status = Status::Missing;
            badge.watch.forget();  // graded again when it appears
            continue;
        }
        if (!badge.watch.changed(file, submission_)) continue;
        badge.status = Status::Unknown;
        if (id != first) cursor_ = k;
        start(id);
        if (waitsForAGrade()) {  // one grade at a time: the others wait
            markStale(registry);
            return arrived;
        }
    }
    return arrived;
}

// While the others wait for their grade, a badge whose file changed since it was graded says
// "..." rather than the grade of the file before (a fix showed the old "compile error").
void Badges::markStale(const ModuleRegistry& registry) {
    for (const auto& m : registry.modules()) {
        const std::string& id = m.desc->id;
        auto it = badges_.find(id);
        if (it == badges_.end() || pending_.count(id)) continue;
        Badge& badge = it->second;
        if (badge.status == Status::Unknown || badge.status == Status::Missing) continue;
        const fs::path file = submission_ / (id + ".glsl");
        if (badge.status == Status::CompileError && !badge.compileError.stale(file)) continue;
        if (badge.watch.stale(file)) badge.status = Status::Unknown;
    }
}

void Badges::markCompileError(const std::string& id) {
    Badge& badge = badges_[id];
    badge.status = Status::CompileError;
    badge.compileError.forget();
    badge.compileError.changed(submission_ / (id + ".glsl"), submission_);
}

bool Badges::upToDate(const std::string& id) const {
    if (pending_.count(id)) return false;
    const Badge& badge = of(id);
    if (badge.status == Status::Missing || badge.status == Status::NotGradedHere) return true;
    return badge.status != Status::Unknown && !badge.watch.stale(submission_ / (id + ".glsl"));
}

void Badges::start(const std::string& id) {
    switch (grades_->start(id)) {
        case platform::StepGrades::Start::Started:
            pending_.insert(id);  // graded, or on its way
            break;
        case platform::StepGrades::Start::NotHere:
            badges_[id].status = Status::NotGradedHere;
            break;
        case platform::StepGrades::Start::Failed:
            badges_[id].status = Status::Fails;
            badges_[id].gradeMessage = "could not start the grade (pbrlab check)";
            break;
    }
}

bool Badges::waitsForAGrade() const {
    return grades_->oneAtATime() && !pending_.empty();
}

}  // namespace pbrlab
