#include "badges.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#ifdef __EMSCRIPTEN__
#include <emscripten.h>
#endif

#include "evaluation_worker.h"
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

#ifdef __EMSCRIPTEN__
// The page's grader (shell.html, web/grader_worker.js): the report of step `id` once it has
// arrived, else empty.
std::optional<std::string> pageGradeResult(const std::string& id) {
    char* text = reinterpret_cast<char*>(EM_ASM_INT(
        {
            const report = pbrlabPage.gradeResult(UTF8ToString($0));
            return report ? allocateUTF8(report) : 0;
        },
        id.c_str()));
    if (!text) return std::nullopt;
    std::string report(text);
    free(text);
    return report;
}
#endif

}  // namespace

Badges::~Badges() {
#ifdef __EMSCRIPTEN__
    return;  // the page's grader finishes its step and is asked nothing more
#endif
    if (job_.pid > 0) {
        kill(job_.pid, SIGKILL);
        waitpid(job_.pid, nullptr, 0);
        std::error_code ec;
        fs::remove(job_.json, ec);
    }
}

std::string Badges::update(const ModuleRegistry& registry, const std::string& first) {
    std::string arrived;
#ifdef __EMSCRIPTEN__
    // The page's grader orders the grades itself (shell.html: the file just written first,
    // then the step on screen): every step whose file changed is asked for at once.
    for (auto it = pending_.begin(); it != pending_.end();) {
        const std::optional<std::string> report = pageGradeResult(*it);
        if (!report) {
            ++it;
            continue;
        }
        takeReport(badges_[*it], *report);
        arrived = *it;
        it = pending_.erase(it);
    }
#else
    if (job_.pid > 0) {
        int status = 0;
        if (waitpid(job_.pid, &status, WNOHANG) == 0) {  // still grading
            markStale(registry);
            return {};
        }
        std::ostringstream text;
        text << std::ifstream(job_.json).rdbuf();
        takeReport(badges_[job_.id], text.str());
        std::error_code ec;
        fs::remove(job_.json, ec);
        arrived = job_.id;
        job_ = {};
    }
#endif
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
#ifndef __EMSCRIPTEN__
        if (job_.pid > 0) markStale(registry);  // one grade at a time: the others wait
        return arrived;
#endif
    }
    return arrived;
}

// While the others wait for their grade, a badge whose file changed since it was graded says
// "..." rather than the grade of the file before (a fix showed the old "compile error").
void Badges::markStale(const ModuleRegistry& registry) {
    for (const auto& m : registry.modules()) {
        const std::string& id = m.desc->id;
        auto it = badges_.find(id);
        if (it == badges_.end() || id == job_.id) continue;
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
    if (job_.pid > 0 && job_.id == id) return false;
    if (pending_.count(id)) return false;
    const Badge& badge = of(id);
    if (badge.status == Status::Missing || badge.status == Status::NotGradedHere) return true;
    return badge.status != Status::Unknown && !badge.watch.stale(submission_ / (id + ".glsl"));
}

void Badges::start(const std::string& id) {
#ifdef __EMSCRIPTEN__
    // A page starts no processes: its grader is a Web Worker (shell.html), given the
    // workspace's files; without one (no OffscreenCanvas) the badge says "ungraded".
    if (!EM_ASM_INT({ return pbrlabPage.grade(UTF8ToString($0)) ? 1 : 0; }, id.c_str())) {
        badges_[id].status = Status::NotGradedHere;
        return;
    }
    pending_.insert(id);  // graded, or on its way (the page answers gradeResult)
    return;
#endif
    job_.id = id;
    job_.json = fs::temp_directory_path() /
                ("pbrlab-badge-" + std::to_string(getpid()) + "-" + id + ".json");
    const std::string exe = fs::read_symlink("/proc/self/exe").string();
    // The same step folders as this process (moduleDirs drops the ones given twice).
    std::vector<std::string> args = {exe};
    for (const fs::path& dir : modulesDirs_) args.insert(args.end(), {"--modules", dir.string()});
    args.insert(args.end(),
                {"check", id, "--submission", submission_.string(), "--json", job_.json.string()});
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t quiet;
    posix_spawn_file_actions_init(&quiet);
    posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&quiet, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = -1;
    if (posix_spawn(&pid, exe.c_str(), &quiet, nullptr, argv.data(), environ) != 0) pid = -1;
    posix_spawn_file_actions_destroy(&quiet);
    job_.pid = pid;
    // The grade yields the cores to the window, as the evaluation thread does (a thread the
    // child starts inherits it; one started before this call would run at nice 0).
    if (pid > 0) setpriority(PRIO_PROCESS, static_cast<id_t>(pid), kBackgroundNice);
    if (pid < 0) {
        badges_[id].status = Status::Fails;
        badges_[id].gradeMessage = "could not start the grade (pbrlab check)";
        job_ = {};
    }
}

}  // namespace pbrlab
