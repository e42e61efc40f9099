#include "course/autograder.h"

#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include "gl/context.h"
#include "grading/stability.h"
#include "render/display.h"
#include "steps/contract.h"
#include "util/error.h"
#include "util/log.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace pbrlab {

namespace {

// Every string in `j` made valid UTF-8 (messages quote compiler logs of students' files).
json sanitized(const json& j) {
    if (j.is_string()) return validUtf8(j.get<std::string>());
    if (j.is_array() || j.is_object()) {
        json out = j;
        for (auto it = out.begin(); it != out.end(); ++it) *it = sanitized(*it);
        return out;
    }
    return j;
}

std::string dumpJson(const json& j, int indent = -1) {
    return j.dump(indent, ' ', false, json::error_handler_t::replace);
}

// The student's and the reference's pictures of the module's scene, and their difference.
void writeImages(LabRenderer& renderer, const LoadedModule& m, const DataPaths& paths,
                 const GradeOptions& o) {
    const ModuleDesc& d = *m.desc;
    const fs::path dir = o.html / d.id;
    fs::create_directories(dir);
    const Scene scene = loadScene(paths.scene(d.scene));
    const ParamValues params(d.params);
    EvalRequest request;
    request.render = {&m,      &params, &scene, StudentSource{o.submission, o.cumulative},
                      nullptr, 192,     192};
    request.render.seamlessCubes = false;
    const Evaluation e = evaluate(renderer, request);
    Image reference = e.render.value;
    for (size_t i = 0; i < e.band.expected.size(); ++i)
        for (int c = 0; c < 3; ++c)
            reference.pixels[i * 4 + size_t(c)] = float(e.band.expected[i][c]);
    writeImage(dir / "student.png", displayImage(e.render.value, d.display, d.components),
               FileDepth::Uint8, true);
    writeImage(dir / "reference.png", displayImage(reference, d.display, d.components),
               FileDepth::Uint8, true);
    // Colour scale: half the largest reference value, so a wrong step reads as bright and
    // rounding stays dark.
    double peak = 0;
    for (const auto& v : e.band.expected)
        for (int c = 0; c < d.components; ++c)
            if (std::isfinite(v[c])) peak = std::max(peak, std::abs(v[c]));
    const double range = std::max(0.5 * peak, 1e-6);
    writeImage(dir / "difference.png",
               differenceImage(e.render.value, reference, d.components, range), FileDepth::Uint8,
               true);
    // The scale the report's colour bar shows beside the difference image.
    writeFileAtomically(dir / "difference.json", json{{"range", range}}.dump() + "\n");
}

// The difference image's colour bar: the false-colour map from 0 to the image's range (errors
// beyond it saturate), and the colours of NaN and Inf.
std::string colourBar(const fs::path& scaleFile) {
    double range = 0;
    try {
        std::ifstream in(scaleFile);
        range = json::parse(in).at("range").get<double>();
    } catch (const std::exception&) {
        return "";
    }
    auto hex = [](const glm::dvec3& c) {
        char text[8];
        std::snprintf(text, sizeof text, "#%02x%02x%02x", int(std::lround(c.r * 255)),
                      int(std::lround(c.g * 255)), int(std::lround(c.b * 255)));
        return std::string(text);
    };
    auto label = [](double v) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3g", v);
        return std::string(text);
    };
    const std::string id = "scale-" + scaleFile.parent_path().filename().string();  // the step
    std::ostringstream s;
    s << "<br><svg width=160 height=44 role=img><title>|student - reference| per pixel (largest "
         "channel): dark 0, bright "
      << label(range) << " or more</title><defs><linearGradient id=" << id << ">";
    for (int i = 0; i <= 8; ++i)
        s << "<stop offset=" << i * 12.5 << "% stop-color=" << hex(falseColor(i / 8.0)) << " />";
    s << "</linearGradient></defs><rect width=160 height=10 fill=url(#" << id << ") />"
      << "<text x=0 y=22 fill=#999 font-size=10>0</text><text x=80 y=22 fill=#999 font-size=10 "
         "text-anchor=middle>"
      << label(range / 2) << "</text><text x=160 y=22 fill=#999 font-size=10 text-anchor=end>&ge;"
      << label(range) << "</text><rect x=0 y=31 width=9 height=9 fill=" << hex(kNanColor)
      << " /><text x=12 y=40 fill=#999 font-size=10>NaN</text><rect x=42 y=31 width=9 height=9 "
         "fill="
      << hex(kInfColor) << " /><text x=54 y=40 fill=#999 font-size=10>Inf</text>"
      << "<text x=160 y=40 fill=#999 font-size=10 text-anchor=end>|error|</text></svg>";
    return s.str();
}

// One module graded in a child process: what the parent keeps while it runs.
struct Child {
    const LoadedModule* module = nullptr;
    size_t slot = 0;  // where its grade goes in the report
    pid_t pid = -1;
    int fd = -1;
    std::chrono::steady_clock::time_point deadline;
    std::string text;  // what it wrote so far
    bool timedOut = false;
    bool outOfBudget = false;  // killed when the submission's time budget ran out
};

// Forks and grades one module in the child, which tells each stage it starts ("stage ...")
// before its result ("result" and one line of JSON), so a crash or a timeout can say where it
// happened.
Child startChild(const LoadedModule& m, const DataPaths& paths, const GradeOptions& o,
                 size_t slot) {
    int fds[2];
    if (pipe(fds) != 0) throw Error("grade: pipe failed");
    pid_t pid = fork();
    if (pid < 0) throw Error("grade: fork failed");
    if (pid == 0) {
        close(fds[0]);
        rlimit limit{o.memoryLimitMb << 20, o.memoryLimitMb << 20};
        setrlimit(RLIMIT_AS, &limit);
        auto send = [&](const std::string& text) {
            for (size_t done = 0; done < text.size();) {
                ssize_t n = write(fds[1], text.data() + done, text.size() - done);
                if (n <= 0) break;
                done += size_t(n);
            }
        };
        std::string out;
        try {
            // llvmpipe starts a rendering thread per processor it sees; under a CPU quota (a
            // container's) only the quota's worth can run.
            if (const int cpus = usableCpus();
                cpus < int(std::thread::hardware_concurrency()) && !std::getenv("LP_NUM_THREADS"))
                setenv("LP_NUM_THREADS", std::to_string(cpus).c_str(), 1);
            auto context = createHeadlessContext();
            LabRenderer renderer(paths);
            GradeOptions options = o;
            options.settings.stage = [&](const std::string& what) {
                send("stage " + validUtf8(what) + "\n");
            };
            out = dumpJson(sanitized(gradeJson(gradeModule(renderer, m, paths, options))));
            // Out now, without tearing down the renderer and the GL context (llvmpipe's threads
            // joined one by one): the kernel frees it all at once.
            send("result\n" + out + "\n");
            _exit(0);
        } catch (const std::exception& e) {
            ModuleGrade failed;
            failed.id = m.desc->id;
            failed.title = m.desc->title;
            failed.status = GradeStatus::Crashed;
            failed.message = e.what();
            out = dumpJson(sanitized(gradeJson(failed)));
        }
        send("result\n" + out + "\n");
        close(fds[1]);
        _exit(0);
    }
    close(fds[1]);
    Child c;
    c.module = &m;
    c.slot = slot;
    c.pid = pid;
    c.fd = fds[0];
    c.deadline =
        std::chrono::steady_clock::now() + std::chrono::milliseconds(long(o.timeoutSeconds * 1000));
    return c;
}

// The grade from what a finished (or killed) child wrote and how it ended.
ModuleGrade finishChild(Child& c, const GradeOptions& o) {
    close(c.fd);
    if (c.timedOut) kill(c.pid, SIGKILL);
    int status = 0;
    waitpid(c.pid, &status, 0);
    ModuleGrade g;
    g.id = c.module->desc->id;
    g.title = c.module->desc->title;
    // The last stage the child announced, and its result when it got that far.
    std::string stage, result;
    {
        std::istringstream lines(c.text);
        for (std::string line; std::getline(lines, line);) {
            if (line.rfind("stage ", 0) == 0) stage = line.substr(6);
            if (line == "result") std::getline(lines, result);
        }
    }
    const bool compiling = stage.size() >= 7 && stage.compare(stage.size() - 7, 7, "compile") == 0;
    if (c.timedOut && c.outOfBudget) {
        g.status = GradeStatus::Timeout;
        g.message = "not finished: grading the whole submission may take " +
                    std::to_string(int(o.budgetSeconds)) + " s, and that ran out during " +
                    (stage.empty() ? std::string("this step") : stage) +
                    " (the steps graded before it took that time)";
        return g;
    }
    if (c.timedOut) {
        g.status = GradeStatus::Timeout;
        g.message = "killed after " + std::to_string(int(o.timeoutSeconds)) + " s" +
                    (compiling ? " while compiling the shader (a macro that expands without end?)"
                               : " during " + stage + " (an endless loop in the shader?)");
        return g;
    }
    try {
        ModuleGrade child = gradeFromJson(json::parse(result));
        child.id = g.id;  // the module graded, whatever the child wrote
        child.title = g.title;
        g = std::move(child);
    } catch (const std::exception&) {
        g.status = GradeStatus::Crashed;
        const std::string how = WIFSIGNALED(status) ? std::string("the grading process died (") +
                                                          strsignal(WTERMSIG(status)) + ")"
                                                    : "the grading process ended without a result";
        g.message = compiling ? how +
                                    " while the GLSL compiler read your file: something in "
                                    "it crashes the compiler (a macro that expands without "
                                    "end, a construct far too large?)"
                              : how + (stage.empty() ? "" : " during " + stage);
    }
    // The score follows from the status here, whatever the child wrote.
    g.score = g.status == GradeStatus::Passed ? g.maxScore : 0;
    return g;
}

// The order children start in: the costliest kinds of step first, the lab order within a kind.
// Estimators are judged by convergence over several sample counts and skies, and the other
// steps that read the environment fill image-based maps; each takes several times an analytic
// step. Started last, one of them would run alone at the end while the other cores idle.
std::vector<size_t> startOrder(const std::vector<GradeJob>& work) {
    auto cost = [&](size_t i) {
        const ModuleDesc& d = *work[i].module->desc;
        if (d.estimator) return 0;
        return (d.needs & (NeedsEnvironment | NeedsPrecomputedMaps)) ? 1 : 2;
    };
    std::vector<size_t> order(work.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return cost(a) < cost(b); });
    return order;
}

// Grades the jobs in children, at most `o.jobs` at a time, each within its time limit.
void gradeInChildren(const std::vector<GradeJob>& work, const DataPaths& paths,
                     const GradeOptions& o, std::vector<ModuleGrade>& grades) {
    if (!work.empty()) preloadHeadlessLibrary();  // inherited by every child
    const size_t jobs = size_t(std::max(1, o.jobs));
    logLine(
        "grade",
        std::to_string(work.size()) + " steps, " + std::to_string(jobs) + " at once" +
            (o.budgetSeconds > 0 ? ", within " + std::to_string(int(o.budgetSeconds)) + " s" : ""));
    using Clock = std::chrono::steady_clock;
    const bool budgeted = o.budgetSeconds > 0;
    const Clock::time_point budgetEnd =
        Clock::now() + std::chrono::milliseconds(long(o.budgetSeconds * 1000));
    std::vector<Child> running;
    const std::vector<size_t> order = startOrder(work);
    size_t next = 0;  // position in `order`
    while (next < work.size() || !running.empty()) {
        while (running.size() < jobs && next < work.size()) {
            if (budgeted && Clock::now() >= budgetEnd) {
                // Not started: said as such, in the order they would have started.
                for (; next < work.size(); ++next) {
                    const GradeJob& job = work[order[next]];
                    ModuleGrade& g = grades[order[next]];
                    g.id = job.module->desc->id;
                    g.title = job.module->desc->title;
                    g.status = GradeStatus::Timeout;
                    g.message = "not graded: grading the whole submission may take " +
                                std::to_string(int(o.budgetSeconds)) +
                                " s, and that ran out before this step (the steps graded "
                                "before it took that time)";
                    if (o.progress) o.progress(g);
                }
                break;
            }
            GradeOptions each = o;
            each.submission = work[order[next]].submission;
            Child c = startChild(*work[order[next]].module, paths, each, order[next]);
            if (budgeted && budgetEnd < c.deadline) {
                c.deadline = budgetEnd;
                c.outOfBudget = true;  // meaningful only if it times out
            }
            running.push_back(std::move(c));
            ++next;
        }
        if (running.empty()) break;  // the budget ran out with nothing left running
        std::vector<pollfd> fds;
        for (const Child& c : running) fds.push_back({c.fd, POLLIN, 0});
        const auto now = std::chrono::steady_clock::now();
        long wait = 1000;
        for (const Child& c : running)
            wait = std::min<long>(
                wait, std::max<long>(
                          0, std::chrono::duration_cast<std::chrono::milliseconds>(c.deadline - now)
                                 .count()));
        poll(fds.data(), fds.size(), int(wait));
        for (size_t i = running.size(); i-- > 0;) {
            Child& c = running[i];
            bool done = false;
            if (fds[i].revents & (POLLIN | POLLHUP | POLLERR)) {
                char buf[65536];
                ssize_t n = read(c.fd, buf, sizeof buf);
                if (n > 0)
                    c.text.append(buf, size_t(n));
                else
                    done = true;
            }
            if (!done && std::chrono::steady_clock::now() >= c.deadline) done = c.timedOut = true;
            if (done) {
                grades[c.slot] = finishChild(c, o);
                if (o.progress) o.progress(grades[c.slot]);
                running.erase(running.begin() + long(i));
            }
        }
    }
}

// What a compiler message means in the contract's terms, where it can tell.

}  // namespace

int cpusOfQuota(const std::string& cgroup2CpuMax, long cgroup1Quota, long cgroup1Period,
                int processors) {
    double quota = -1, period = -1;
    if (!cgroup2CpuMax.empty()) {
        std::istringstream in(cgroup2CpuMax);  // "max 100000" or "50000 100000"
        std::string q;
        in >> q >> period;
        if (q != "max" && in) quota = std::atof(q.c_str());
    } else if (cgroup1Quota > 0 && cgroup1Period > 0) {
        quota = double(cgroup1Quota), period = double(cgroup1Period);
    }
    processors = std::max(1, processors);
    if (quota <= 0 || period <= 0) return processors;
    return std::clamp(int(std::ceil(quota / period)), 1, processors);
}

int usableCpus() {
    auto read = [](const std::string& file) {
        std::ifstream in(file);
        std::string text;
        std::getline(in, text);
        return text;
    };
    auto number = [&](const std::string& file) {
        const std::string text = read(file);
        return text.empty() ? -1L : std::atol(text.c_str());
    };
    // This process's cgroup ("0::/a/b" under cgroup v2, "N:cpu,cpuacct:/a/b" under v1; "/" in
    // a container that has a cgroup namespace) and each above it: the smallest quota counts.
    std::string v2 = "/", v1 = "/";
    {
        std::ifstream in("/proc/self/cgroup");
        for (std::string line; std::getline(in, line);) {
            const size_t a = line.find(':'), b = line.find(':', a + 1);
            if (a == std::string::npos || b == std::string::npos) continue;
            const std::string controllers = "," + line.substr(a + 1, b - a - 1) + ",";
            if (controllers == ",,") v2 = line.substr(b + 1);
            if (controllers.find(",cpu,") != std::string::npos) v1 = line.substr(b + 1);
        }
    }
    const int processors = int(std::thread::hardware_concurrency());
    int cpus = std::max(1, processors);
    for (fs::path dir = v2;; dir = dir.parent_path()) {
        const std::string d = dir.string() == "/" ? "" : dir.string();
        cpus = std::min(cpus,
                        cpusOfQuota(read("/sys/fs/cgroup" + d + "/cpu.max"), -1, -1, processors));
        if (dir == dir.parent_path()) break;
    }
    for (fs::path dir = v1;; dir = dir.parent_path()) {
        const std::string d = "/sys/fs/cgroup/cpu" + (dir.string() == "/" ? "" : dir.string());
        cpus = std::min(cpus, cpusOfQuota("", number(d + "/cpu.cfs_quota_us"),
                                          number(d + "/cpu.cfs_period_us"), processors));
        if (dir == dir.parent_path()) break;
    }
    return cpus;
}

std::string jsonText(const json& report) {
    return dumpJson(report, 2);
}

ModuleGrade gradeModule(LabRenderer& renderer, const LoadedModule& m, const DataPaths& paths,
                        const GradeOptions& o) {
    return gradeModuleHere(renderer, m, paths, {o.submission, o.cumulative}, o.settings, [&] {
        if (!o.html.empty()) writeImages(renderer, m, paths, o);
    });
}

std::vector<ModuleGrade> gradeJobs(const std::vector<GradeJob>& jobs, const DataPaths& paths,
                                   const GradeOptions& options) {
    std::vector<ModuleGrade> grades(jobs.size());
    gradeInChildren(jobs, paths, options, grades);
    return grades;
}

GradeReport gradeSubmission(const ModuleRegistry& modules, const DataPaths& paths,
                            const GradeOptions& o) {
    auto start = std::chrono::steady_clock::now();
    GradeReport report;
    report.submission = o.submission;
    std::vector<GradeJob> work;
    std::vector<size_t> slots;  // where each job's grade goes in the report
    for (const auto& m : modules.modules()) {
        if (!o.modules.empty() &&
            std::find(o.modules.begin(), o.modules.end(), m.desc->id) == o.modules.end())
            continue;
        const fs::path file = o.submission / (m.desc->id + ".glsl");
        ModuleGrade g;
        g.id = m.desc->id;
        g.title = m.desc->title;
        try {
            std::error_code ec;
            const bool present = fs::exists(fs::symlink_status(file, ec));
            if (!present) {
                g.status = GradeStatus::Missing;
                g.message = file.filename().string() + " not found";
            } else if (std::string why = screenStudentFile(file, o.submission); !why.empty()) {
                g.status = GradeStatus::Failed;
                g.message = file.string() + ": " + why;
            } else {
                work.push_back({&m, o.submission});
                slots.push_back(report.modules.size());
            }
        } catch (const std::exception& e) {
            // Whatever went wrong with this file costs this step only.
            g.status = GradeStatus::Failed;
            g.message = file.string() + ": " + e.what();
        }
        report.modules.push_back(std::move(g));
    }
    std::vector<ModuleGrade> graded = gradeJobs(work, paths, o);
    for (size_t i = 0; i < graded.size(); ++i) report.modules[slots[i]] = std::move(graded[i]);
    for (ModuleGrade& g : report.modules) {
        if (o.scoring)
            o.scoring(g);
        else
            g.score = g.status == GradeStatus::Passed ? g.maxScore : 0;
        g.message = validUtf8(g.message);
        g.score = roundPoints(g.score);
        g.maxScore = roundPoints(g.maxScore);
        report.score = addPoints(report.score, g.score);
        report.maxScore = addPoints(report.maxScore, g.maxScore);
    }
    report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

double addPoints(double a, double b) {
    return fromMicroPoints(toMicroPoints(a) + toMicroPoints(b));
}

std::string formatPoints(double points) {
    const std::int64_t micro = toMicroPoints(points);
    const std::uint64_t magnitude = micro < 0 ? 0 - std::uint64_t(micro) : std::uint64_t(micro);
    std::string text = (micro < 0 ? "-" : "") + std::to_string(magnitude / 1000000);
    std::string fraction = std::to_string(magnitude % 1000000);
    fraction.insert(0, 6 - fraction.size(), '0');
    while (!fraction.empty() && fraction.back() == '0') fraction.pop_back();
    return fraction.empty() ? text : text + "." + fraction;
}

json toJson(const GradeReport& r) {
    json modules = json::array();
    for (const auto& g : r.modules) modules.push_back(gradeJson(g));
    return {{"submission", r.submission.string()},
            {"score", roundPoints(r.score)},
            {"max_score", roundPoints(r.maxScore)},
            {"seconds", r.seconds},
            {"modules", modules}};
}

json toGradescope(const GradeReport& r) {
    json tests = json::array();
    std::string summary;
    for (const auto& g : r.modules) {
        std::string output =
            std::string(nameOf(g.status)) + (g.message.empty() ? "" : ": " + g.message);
        tests.push_back({{"name", g.id + ": " + g.title},
                         {"score", roundPoints(g.score)},
                         {"max_score", roundPoints(g.maxScore)},
                         {"status", g.status == GradeStatus::Passed ? "passed" : "failed"},
                         {"output", output}});
        summary += g.id + " " + std::string(nameOf(g.status)) + "\n";
    }
    return {{"score", roundPoints(r.score)},
            {"execution_time", r.seconds},
            {"output", summary},
            {"tests", tests}};
}

void writeFileAtomically(const fs::path& file, const std::string& text) {
    if (file.has_parent_path()) fs::create_directories(file.parent_path());
    fs::path tmp = file;
    tmp += ".tmp" + std::to_string(getpid());
    {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        if (!out) throw Error(tmp.string() + ": cannot write");
    }
    fs::rename(tmp, file);
}

void writeHtml(const GradeReport& r, const fs::path& folder) {
    auto escape = [](const std::string& s) {
        std::string o;
        for (char c : s)
            o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
        return o;
    };
    std::ostringstream h;
    h << "<!doctype html><meta charset=utf-8><title>pbrlab grade</title><style>"
         "body{font-family:sans-serif;background:#1c1d21;color:#ddd;max-width:1100px;margin:auto}"
         "td,th{padding:6px;border-bottom:1px solid #333;vertical-align:top}"
         ".passed{color:#6d6}.failed,.compile_error,.crashed,.timeout{color:#f85}.missing{color:#"
         "999}"
         "pre{white-space:pre-wrap;font-size:12px}</style>"
      << "<h1>pbrlab: " << escape(r.submission.string()) << "</h1><p>score "
      << formatPoints(r.score) << " / " << formatPoints(r.maxScore) << " (" << r.seconds
      << " s)</p><table><tr><th>step</th><th>status</th>"
      << "<th>student</th><th>reference</th><th>difference</th><th>feedback</th></tr>\n";
    for (const auto& g : r.modules) {
        bool images = fs::exists(folder / g.id / "student.png");
        h << "<tr><td>" << escape(g.id) << "<br><small>" << escape(g.title)
          << "</small></td><td class=" << g.status << ">" << g.status << "<br>"
          << formatPoints(g.score) << " / " << formatPoints(g.maxScore) << "</td>";
        for (const std::string img : {"student", "reference", "difference"})
            h << "<td>" << (images ? "<img width=160 src=\"" + g.id + "/" + img + ".png\">" : "")
              << (images && img == "difference" ? colourBar(folder / g.id / "difference.json") : "")
              << "</td>";
        h << "<td><pre>" << escape(g.message) << "</pre>";
        if (!g.checks.empty()) {
            h << "<details><summary>" << g.checks.size() << " checks</summary><ul>";
            for (const auto& c : g.checks) {
                const bool passed = c.value("passed", false), deducted = c.value("deducted", true);
                h << "<li class="
                  << (passed     ? "passed"
                      : deducted ? "failed"
                                 : "missing")
                  << ">"
                  << (passed     ? "ok"
                      : deducted ? "FAILED"
                                 : "reported")
                  << " " << escape(c.value("name", "")) << ": <small>"
                  << escape(c.value("detail", "")) << "</small></li>";
            }
            h << "</ul></details>";
        }
        h << "</td></tr>\n";
    }
    h << "</table>";
    writeFileAtomically(folder / "index.html", h.str());
}

}  // namespace pbrlab
