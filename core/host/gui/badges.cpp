#include "badges.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "evaluation_worker.h"
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

Badges::~Badges() {
    if (job_.pid > 0) {
        kill(job_.pid, SIGKILL);
        waitpid(job_.pid, nullptr, 0);
        std::error_code ec;
        fs::remove(job_.json, ec);
    }
}

std::string Badges::update(const ModuleRegistry& registry) {
    std::string arrived;
    if (job_.pid > 0) {
        int status = 0;
        if (waitpid(job_.pid, &status, WNOHANG) == 0) return {};  // still grading
        Badge& badge = badges_[job_.id];
        try {
            const nlohmann::json report = nlohmann::json::parse(std::ifstream(job_.json));
            const nlohmann::json& g = report.at("modules").at(0);
            const std::string result = g.at("status");
            badge.status = result == "passed"          ? Status::Passes
                           : result == "compile_error" ? Status::CompileError
                                                       : Status::Fails;
            badge.gradeMessage = g.value("message", "");
        } catch (const std::exception&) {
            badge.status = Status::Fails;
            badge.gradeMessage = "the grade did not finish";
        }
        std::error_code ec;
        fs::remove(job_.json, ec);
        arrived = job_.id;
        job_ = {};
    }
    const auto& ms = registry.modules();
    for (size_t k = 0; k < ms.size(); ++k) {
        cursor_ = (cursor_ + 1) % ms.size();
        const std::string& id = ms[cursor_].desc->id;
        Badge& badge = badges_[id];
        fs::path file = submission_.empty() ? fs::path() : submission_ / (id + ".glsl");
        if (file.empty() || !fs::exists(file)) {
            badge.status = Status::Missing;
            badge.watch.forget();  // graded again when it appears
            continue;
        }
        if (!badge.watch.changed(file, submission_)) continue;
        badge.status = Status::Unknown;
        start(id);
        return arrived;
    }
    return arrived;
}

bool Badges::upToDate(const std::string& id) const {
    if (job_.pid > 0 && job_.id == id) return false;
    const Badge& badge = of(id);
    if (badge.status == Status::Missing || badge.status == Status::NotGradedHere) return true;
    return badge.status != Status::Unknown && !badge.watch.stale(submission_ / (id + ".glsl"));
}

void Badges::start(const std::string& id) {
#ifdef __EMSCRIPTEN__
    badges_[id].status = Status::NotGradedHere;  // a page starts no processes
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
