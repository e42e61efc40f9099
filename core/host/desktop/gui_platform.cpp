// The desktop's side of the GUI's platform (gui/platform.h): grades and console commands as
// child processes of this executable, at background priority; GLFW's window drawn each frame.
#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "gui/platform.h"

namespace fs = std::filesystem;

namespace pbrlab::platform {

namespace {

// The evaluation thread and every thread it starts (llvmpipe's, parallelFor's: a new thread
// inherits its creator's nice value on Linux), and the badges' grading processes, yield the
// cores to the window's thread: nice 10 weighs 110 against nice 0's 1024 in the scheduler, so
// with both cores busy the frames still get most of one.
constexpr int kBackgroundNice = 10;

std::vector<char*> argvOf(std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    return argv;
}

// One grade at a time, `pbrlab check ID --json FILE` with its output silenced; its report is
// the file it writes.
class ProcessGrades final : public StepGrades {
public:
    ProcessGrades(std::vector<fs::path> modulesDirs, fs::path submission)
        : modulesDirs_(std::move(modulesDirs)), submission_(std::move(submission)) {}
    ~ProcessGrades() override {
        if (pid_ > 0) {
            kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
            std::error_code ec;
            fs::remove(json_, ec);
        }
    }

    Start start(const std::string& id) override {
        id_ = id;
        json_ = fs::temp_directory_path() /
                ("pbrlab-badge-" + std::to_string(getpid()) + "-" + id + ".json");
        const std::string exe = fs::read_symlink("/proc/self/exe").string();
        // The same step folders as this process (moduleDirs drops the ones given twice).
        std::vector<std::string> args = {exe};
        for (const fs::path& dir : modulesDirs_)
            args.insert(args.end(), {"--modules", dir.string()});
        args.insert(args.end(),
                    {"check", id, "--submission", submission_.string(), "--json", json_.string()});
        std::vector<char*> argv = argvOf(args);
        posix_spawn_file_actions_t quiet;
        posix_spawn_file_actions_init(&quiet);
        posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&quiet, 2, "/dev/null", O_WRONLY, 0);
        pid_t pid = -1;
        if (posix_spawn(&pid, exe.c_str(), &quiet, nullptr, argv.data(), environ) != 0) pid = -1;
        posix_spawn_file_actions_destroy(&quiet);
        if (pid < 0) return Start::Failed;
        pid_ = pid;
        // The grade yields the cores to the window, as the evaluation thread does (a thread the
        // child starts inherits it; one started before this call would run at nice 0).
        setpriority(PRIO_PROCESS, static_cast<id_t>(pid), kBackgroundNice);
        return Start::Started;
    }

    std::optional<std::string> report(const std::string& id) override {
        if (pid_ <= 0 || id != id_) return std::nullopt;
        int status = 0;
        if (waitpid(pid_, &status, WNOHANG) == 0) return std::nullopt;  // still grading
        std::ostringstream text;
        text << std::ifstream(json_).rdbuf();
        std::error_code ec;
        fs::remove(json_, ec);
        pid_ = -1;
        return text.str();
    }

    bool oneAtATime() const override { return true; }

private:
    std::vector<fs::path> modulesDirs_;
    fs::path submission_;
    pid_t pid_ = -1;  // the grade running, if any: step id_'s, into json_
    std::string id_;
    fs::path json_;
};

// The process and the thread that reads its one pipe (stdout is block-buffered in a pipe, so
// the two may interleave differently than on a terminal).
class ChildPbrlab final : public PbrlabProcess {
public:
    ChildPbrlab(pid_t pid, int pipe, std::function<void(const std::string&)> output)
        : pid_(pid), pipe_(pipe) {
        reader_ = std::thread([this, output = std::move(output)] {
            char buffer[4096];
            for (ssize_t n; (n = read(pipe_, buffer, sizeof buffer)) != 0;) {
                if (n < 0 && errno == EINTR) continue;
                if (n < 0) break;
                output(std::string(buffer, size_t(n)));
            }
            int status = 0;
            waitpid(pid_, &status, 0);
            output(WIFEXITED(status)
                       ? "(exit status " + std::to_string(WEXITSTATUS(status)) + ")\n"
                       : "(stopped by signal " + std::to_string(WTERMSIG(status)) + ")\n");
            finished_ = true;
        });
    }
    ~ChildPbrlab() override {
        if (!finished_) kill(-pid_, SIGTERM);  // its process group: grade's children too
        if (reader_.joinable()) reader_.join();
        close(pipe_);
    }
    bool finished() const override { return finished_; }

private:
    pid_t pid_;
    int pipe_;
    std::atomic<bool> finished_ = false;
    std::thread reader_;  // last: started once the members above exist
};

std::set<std::string> threadIds() {  // this process's, from /proc/self/task
    std::set<std::string> ids;
    if (DIR* dir = opendir("/proc/self/task")) {
        while (const dirent* e = readdir(dir))
            if (e->d_name[0] != '.') ids.insert(e->d_name);
        closedir(dir);
    }
    return ids;
}

}  // namespace

std::unique_ptr<StepGrades> stepGrades(std::vector<fs::path> modulesDirs, fs::path submission) {
    return std::make_unique<ProcessGrades>(std::move(modulesDirs), std::move(submission));
}

std::unique_ptr<PbrlabProcess> startPbrlab(const std::vector<std::string>& args,
                                           std::function<void(const std::string&)> output) {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) {
        output("error: cannot make a pipe\n");
        return nullptr;
    }
    std::vector<std::string> words = {"pbrlab"};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv = argvOf(words);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
    posix_spawn_file_actions_adddup2(&actions, fds[1], 2);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attributes, 0);
    pid_t pid = -1;
    const int failed =
        posix_spawn(&pid, "/proc/self/exe", &actions, &attributes, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    close(fds[1]);
    if (failed) {
        close(fds[0]);
        output(std::string("error: cannot start pbrlab: ") + strerror(failed) + "\n");
        return nullptr;
    }
    return std::make_unique<ChildPbrlab>(pid, fds[0], std::move(output));
}

bool runFrames(const std::function<bool()>& frame,
               const std::function<void(const std::exception&)>&) {
    while (frame()) {
    }
    return true;
}

bool windowKeepsItsPixels() {
    return false;
}
bool skipsQuietFrames() {
    return false;
}
bool inputArrived() {
    return false;
}
void frameDrawn() {}
std::function<bool()> inputPending() {
    return {};
}

void backgroundPriorityForThisThread() {
    setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), kBackgroundNice);
}

void backgroundPriorityForThreadsStartedBy(const std::function<void()>& start) {
    const std::set<std::string> before = threadIds();
    start();
    for (const std::string& tid : threadIds())
        if (!before.count(tid))
            setpriority(PRIO_PROCESS, static_cast<id_t>(std::stoi(tid)), kBackgroundNice);
}

}  // namespace pbrlab::platform
