#include "grade.h"

#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>

#include "check.h"
#include "gl/context.h"
#include "pbrlab/display.h"
#include "pbrlab/error.h"
#include "stability.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace pbrlab {

namespace {

constexpr std::uintmax_t kMaxStudentFileBytes = 10u * 1024 * 1024;

json statsJson(const ErrorStats& s, const Tolerance& t, bool nonNegative) {
    return {{"pixels", s.compared},
            {"max_error", s.maxError},
            {"mean_error", s.meanError},
            {"max_abs", s.maxAbs},
            {"nan", s.nanCount},
            {"inf", s.infCount},
            {"negative", s.negativeCount},
            {"over_tolerance", s.overCount},
            {"tolerance", t.maxError},
            {"floor", t.floor},
            {"passed", s.passes(t, nonNegative)}};
}

std::string firstLineComment(const fs::path& file) {
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    for (const char* prefix : {"// mistake:", "//"})
        if (line.rfind(prefix, 0) == 0) {
            line = line.substr(std::strlen(prefix));
            break;
        }
    size_t b = line.find_first_not_of(' ');
    return b == std::string::npos ? file.stem().string() : line.substr(b);
}

double meanDifference(const Image& a, const Image& b, int components) {
    double sum = 0;
    int n = 0;
    for (size_t i = 0; i + 3 < a.pixels.size() && i + 3 < b.pixels.size(); i += 4) {
        if (a.pixels[i + 3] != 1 || b.pixels[i + 3] != 1) continue;  // surfaces only
        for (int c = 0; c < components; ++c) {
            double d = std::abs(double(a.pixels[i + size_t(c)]) - b.pixels[i + size_t(c)]);
            sum += std::isfinite(d) ? d / (1 + std::abs(double(b.pixels[i + size_t(c)]))) : 1;
            ++n;
        }
    }
    return n ? sum / n : 0;
}

struct Renders {
    Image scene, probe;
};

Renders renderBoth(LabRenderer& r, const LoadedModule& m, const ParamValues& p, const Scene& s,
                   const StudentSource& src, int size) {
    return {r.renderScene(m, p, s, src, size, size, false).value,
            r.renderProbe(m, p, s, src).value};
}

std::string where(const ErrorStats& s, const Surface& at) {
    std::ostringstream o;
    o.precision(4);
    o << "largest error " << s.maxError << " at pixel (" << s.worstX << ", " << s.worstY
      << "): yours (" << s.worstGpu.x << ", " << s.worstGpu.y << ", " << s.worstGpu.z
      << "), reference (" << s.worstRef.x << ", " << s.worstRef.y << ", " << s.worstRef.z
      << "); inputs N.V " << glm::dot(at.normal, at.view) << ", N.L "
      << glm::dot(at.normal, at.light) << ", roughness " << at.roughness << ", metallic "
      << at.metallic;
    return o.str();
}

// Runs in the child process: everything GL lives and dies here.
ModuleGrade gradeModule(const LoadedModule& m, const DataPaths& paths, const GradeOptions& o) {
    const ModuleDesc& d = *m.desc;
    ModuleGrade g;
    g.id = d.id;
    g.title = d.title;
    auto context = createHeadlessContext();
    LabRenderer renderer(paths);
    ParamValues params(d.params);
    StudentSource source{o.submission, o.cumulative};
    Scene scene = loadScene(paths.scene(d.scene));
    try {
        CheckResult c = checkModule(renderer, m, params, scene, source, o.size, o.size);
        g.metrics["scene"] = statsJson(c.scene, d.tolerance, d.nonNegative);
        g.metrics["probe"] = statsJson(c.probe, d.tolerance, d.nonNegative);
        bool passed = c.passed;
        const ErrorStats* worst = c.scene.passes(d.tolerance, d.nonNegative) ? &c.probe : &c.scene;
        // Direct-lab steps shown on the one-light sphere are also checked on the lesson's grid
        // of four lights (a sum over one light only passes the sphere).
        if (d.lab == "direct" && d.scene != "sphere-grid") {
            Scene grid = loadScene(paths.scene("sphere-grid"));
            CheckResult cg = checkModule(renderer, m, params, grid, source, o.size, o.size);
            g.metrics["grid"] = statsJson(cg.scene, d.tolerance, d.nonNegative);
            if (passed && !cg.passed) worst = &cg.scene;
            passed = passed && cg.passed;
        }
        // Robustness on the extreme inputs: reported, not deducted (DESIGN.md).
        StabilityResult st = stabilitySweep(renderer, m, scene, source);
        g.metrics["robustness"] = {{"nan", st.gpu.nanCount},
                                   {"inf", st.gpu.infCount},
                                   {"negative", d.nonNegative ? st.gpu.negativeCount : 0},
                                   {"first_problem", st.firstProblem}};
        // Invariants of the student's function, where the module defines them: reported.
        if (d.invariants) {
            EvaluateFn evaluate = [&](const std::vector<Surface>& surfaces) {
                const int width = 64, height = int((surfaces.size() + width - 1) / width);
                std::vector<Surface> padded = surfaces;
                padded.resize(size_t(width) * height);
                RenderResult r =
                    renderer.renderSurfaces(m, params, scene, source, padded, width, height);
                std::vector<glm::dvec3> values;
                for (size_t i = 0; i < surfaces.size(); ++i)
                    values.emplace_back(r.value.pixels[i * 4], r.value.pixels[i * 4 + 1],
                                        r.value.pixels[i * 4 + 2]);
                return values;
            };
            json list = json::array();
            for (const InvariantResult& inv : d.invariants(evaluate)) {
                list.push_back({{"name", inv.name},
                                {"measured", inv.measured},
                                {"expected", inv.expected},
                                {"holds", inv.holds}});
                if (!inv.holds)
                    g.message += (g.message.empty() ? "" : "; ") + std::string("invariant ") +
                                 inv.name + " = " + std::to_string(inv.measured) + ", expected " +
                                 inv.expected;
            }
            g.metrics["invariants"] = list;
        }
        g.status = passed ? "passed" : "failed";
        g.score = passed ? g.maxScore : 0;
        if (!passed) {
            // Which surface the worst pixel saw: render again with surfaces read back.
            RenderResult yours =
                renderer.renderScene(m, params, scene, source, o.size, o.size, true);
            std::string message;
            if (worst == &c.probe) {
                auto grid = probeSurfaces(d.probe);
                message =
                    "probe: " +
                    where(c.probe,
                          grid[size_t(c.probe.worstY) * d.probe.width + size_t(c.probe.worstX)]);
            } else if (worst->worstX >= 0) {
                message =
                    "scene: " +
                    where(*worst,
                          yours.surfaces[size_t(worst->worstY) * o.size + size_t(worst->worstX)]);
            }
            if (worst->nanCount + worst->infCount > 0)
                message += "; " + std::to_string(worst->nanCount) + " NaN and " +
                           std::to_string(worst->infCount) + " Inf pixels";
            // Name the mistake when the output is closer to a known one than to the solution.
            Renders student = renderBoth(renderer, m, params, scene, source, 64);
            Renders solution = renderBoth(renderer, m, params, scene, {}, 64);
            double toSolution = meanDifference(student.scene, solution.scene, d.components) +
                                meanDifference(student.probe, solution.probe, d.components);
            std::string best;
            double bestDistance = 1e300;
            fs::path mistakes = m.sourceDir / "mistakes";
            if (fs::exists(mistakes))
                for (const auto& f : fs::directory_iterator(mistakes)) {
                    if (f.path().extension() != ".glsl") continue;
                    fs::path tmp =
                        fs::temp_directory_path() / ("pbrlab-mistake-" + std::to_string(getpid()));
                    fs::create_directories(tmp);
                    fs::copy_file(f.path(), tmp / (d.id + ".glsl"),
                                  fs::copy_options::overwrite_existing);
                    try {
                        Renders r = renderBoth(renderer, m, params, scene, {tmp, false}, 64);
                        double dist = meanDifference(student.scene, r.scene, d.components) +
                                      meanDifference(student.probe, r.probe, d.components);
                        if (dist < bestDistance)
                            bestDistance = dist, best = firstLineComment(f.path());
                    } catch (const Error&) {
                    }
                    fs::remove_all(tmp);
                }
            if (!best.empty() && bestDistance < 0.25 * toSolution)
                message = "looks like: " + best + ". " + message;
            g.message = message + (g.message.empty() ? "" : "; " + g.message);
        }
        if (!o.html.empty()) {
            fs::path dir = o.html / d.id;
            fs::create_directories(dir);
            RenderResult yours = renderer.renderScene(m, params, scene, source, 192, 192, true);
            Scene bound = applyParamBindings(scene, d, params);
            ReferenceContext ctx = referenceContext(bound, params);
            if (d.needs & NeedsEnvironment) ctx.ibl = &renderer.environmentInputs(bound);
            std::vector<glm::dvec3> reference;
            compareWithReference(yours.value, yours.surfaces, d, ctx, &reference);
            Image ref = yours.value;
            for (size_t i = 0; i < reference.size(); ++i)
                for (int c = 0; c < 3; ++c) ref.pixels[i * 4 + size_t(c)] = float(reference[i][c]);
            writeImage(dir / "student.png", displayImage(yours.value, d.display, d.components),
                       FileDepth::Uint8, true);
            writeImage(dir / "reference.png", displayImage(ref, d.display, d.components),
                       FileDepth::Uint8, true);
            // Colour scale: half the largest reference value, so a wrong step reads as bright
            // and rounding stays dark.
            double peak = 0;
            for (const auto& v : reference)
                for (int c = 0; c < d.components; ++c)
                    if (std::isfinite(v[c])) peak = std::max(peak, std::abs(v[c]));
            writeImage(dir / "difference.png",
                       differenceImage(yours.value, ref, d.components, std::max(0.5 * peak, 1e-6)),
                       FileDepth::Uint8, true);
        }
    } catch (const ShaderError& e) {
        g.status = "compile_error";
        g.score = 0;
        g.message = e.what();
    } catch (const std::exception& e) {
        g.status = "failed";
        g.score = 0;
        g.message = e.what();
    }
    return g;
}

json gradeJson(const ModuleGrade& g) {
    return {{"id", g.id},          {"title", g.title},        {"status", g.status},
            {"score", g.score},    {"max_score", g.maxScore}, {"metrics", g.metrics},
            {"message", g.message}};
}

// Forks, grades one module in the child, and reads its JSON through a pipe, within the time
// limit. Anything else (a signal, no answer) is "crashed"; running out of time is "timeout".
ModuleGrade gradeIsolated(const LoadedModule& m, const DataPaths& paths, const GradeOptions& o) {
    ModuleGrade g;
    g.id = m.desc->id;
    g.title = m.desc->title;
    int fds[2];
    if (pipe(fds) != 0) throw Error("grade: pipe failed");
    pid_t pid = fork();
    if (pid < 0) throw Error("grade: fork failed");
    if (pid == 0) {
        close(fds[0]);
        rlimit limit{o.memoryLimitMb << 20, o.memoryLimitMb << 20};
        setrlimit(RLIMIT_AS, &limit);
        std::string out;
        try {
            out = gradeJson(gradeModule(m, paths, o)).dump();
        } catch (const std::exception& e) {
            ModuleGrade failed;
            failed.id = m.desc->id;
            failed.title = m.desc->title;
            failed.status = "crashed";
            failed.message = e.what();
            out = gradeJson(failed).dump();
        }
        for (size_t done = 0; done < out.size();) {
            ssize_t n = write(fds[1], out.data() + done, out.size() - done);
            if (n <= 0) break;
            done += size_t(n);
        }
        close(fds[1]);
        _exit(0);
    }
    close(fds[1]);
    std::string text;
    auto deadline =
        std::chrono::steady_clock::now() + std::chrono::milliseconds(long(o.timeoutSeconds * 1000));
    bool timedOut = false;
    for (;;) {
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                        deadline - std::chrono::steady_clock::now())
                        .count();
        if (left <= 0) {
            timedOut = true;
            break;
        }
        pollfd p{fds[0], POLLIN, 0};
        int ready = poll(&p, 1, int(std::min<long>(left, 1000)));
        if (ready < 0) break;
        if (ready == 0) continue;
        char buf[65536];
        ssize_t n = read(fds[0], buf, sizeof buf);
        if (n <= 0) break;
        text.append(buf, size_t(n));
    }
    close(fds[0]);
    if (timedOut) kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    if (timedOut) {
        g.status = "timeout";
        g.message = "killed after " + std::to_string(int(o.timeoutSeconds)) +
                    " s (an endless loop in the shader?)";
        return g;
    }
    try {
        json j = json::parse(text);
        g.status = j.at("status");
        g.score = j.at("score");
        g.maxScore = j.at("max_score");
        g.metrics = j.at("metrics");
        g.message = j.at("message");
    } catch (const std::exception&) {
        g.status = "crashed";
        g.message = WIFSIGNALED(status)
                        ? std::string("the grading process died: ") + strsignal(WTERMSIG(status))
                        : "the grading process ended without a result";
    }
    return g;
}

}  // namespace

std::string screenStudentFile(const fs::path& file, const fs::path& submission) {
    std::error_code ec;
    if (fs::is_symlink(file, ec) && !isInside(fs::canonical(file, ec), submission))
        return "refused: it is a link to a file outside the submission folder";
    if (!isInside(file, submission)) return "refused: outside the submission folder";
    auto size = fs::file_size(file, ec);
    if (ec) return "cannot read it: " + ec.message();
    if (size > kMaxStudentFileBytes) return "refused: larger than 10 MB";
    std::ifstream in(file, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find('\0') != std::string::npos) return "refused: it contains NUL bytes (not text)";
    return {};
}

GradeReport gradeSubmission(const ModuleRegistry& modules, const DataPaths& paths,
                            const GradeOptions& o) {
    auto start = std::chrono::steady_clock::now();
    GradeReport report;
    report.submission = o.submission;
    for (const auto& m : modules.modules()) {
        if (!o.modules.empty() &&
            std::find(o.modules.begin(), o.modules.end(), m.desc->id) == o.modules.end())
            continue;
        fs::path file = o.submission / (m.desc->id + ".glsl");
        ModuleGrade g;
        g.id = m.desc->id;
        g.title = m.desc->title;
        if (!fs::exists(file) && !fs::is_symlink(file)) {
            g.status = "missing";
            g.message = file.filename().string() + " not found";
        } else if (std::string why = screenStudentFile(file, o.submission); !why.empty()) {
            g.status = "failed";
            g.message = file.string() + ": " + why;
        } else {
            g = gradeIsolated(m, paths, o);
        }
        report.score += g.score;
        report.maxScore += g.maxScore;
        report.modules.push_back(std::move(g));
    }
    report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

json toJson(const GradeReport& r) {
    json modules = json::array();
    for (const auto& g : r.modules) modules.push_back(gradeJson(g));
    return {{"submission", r.submission.string()},
            {"score", r.score},
            {"max_score", r.maxScore},
            {"seconds", r.seconds},
            {"modules", modules}};
}

json toGradescope(const GradeReport& r) {
    json tests = json::array();
    std::string summary;
    for (const auto& g : r.modules) {
        std::string output = g.status + (g.message.empty() ? "" : ": " + g.message);
        tests.push_back({{"name", g.id + ": " + g.title},
                         {"score", g.score},
                         {"max_score", g.maxScore},
                         {"status", g.status == "passed" ? "passed" : "failed"},
                         {"output", output}});
        summary += g.id + " " + g.status + "\n";
    }
    return {
        {"score", r.score}, {"execution_time", r.seconds}, {"output", summary}, {"tests", tests}};
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
      << "<h1>pbrlab: " << escape(r.submission.string()) << "</h1><p>score " << r.score << " / "
      << r.maxScore << " (" << r.seconds << " s)</p><table><tr><th>step</th><th>status</th>"
      << "<th>student</th><th>reference</th><th>difference</th><th>feedback</th></tr>\n";
    for (const auto& g : r.modules) {
        bool images = fs::exists(folder / g.id / "student.png");
        h << "<tr><td>" << escape(g.id) << "<br><small>" << escape(g.title)
          << "</small></td><td class=" << g.status << ">" << g.status << "<br>" << g.score << " / "
          << g.maxScore << "</td>";
        for (const char* img : {"student", "reference", "difference"})
            h << "<td>" << (images ? "<img width=160 src=\"" + g.id + "/" + img + ".png\">" : "")
              << "</td>";
        h << "<td><pre>" << escape(g.message) << "</pre></td></tr>\n";
    }
    h << "</table>";
    writeFileAtomically(folder / "index.html", h.str());
}

}  // namespace pbrlab
