// The commands that go over every step at once: stability, gallery.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "grading/stability.h"
#include "session.h"
#include "steps/contract.h"
#include "table.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

class StabilityCommand : public Command {
public:
    StabilityCommand()
        : Command("stability",
                  "Run every module (or the given ids) on the extreme inputs: NaN/Inf/negatives") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("steps", ids_, help::steps);
        cmd.add_option("--submission", submission_,
                       "Sweep the student's <id>.glsl files instead of the solutions");
    }
    int run(const GlobalOptions& global) override {
        Session session(global);
        std::printf("%-12s %8s %8s %8s %8s %12s  %s\n", "module", "gpu NaN", "gpu Inf", "gpu neg",
                    "ref bad", "worst/tol", "first problem");
        int bad = 0;
        for (const auto& m : session.modules->modules()) {
            if (!ids_.empty() && std::find(ids_.begin(), ids_.end(), m.desc->id) == ids_.end())
                continue;
            Scene scene = loadScene(session.paths.scene(m.desc->scene));
            StudentSource source{submission_, false};
            if (!submission_.empty() && !fs::exists(fs::path(submission_) / (m.desc->id + ".glsl")))
                continue;  // nothing of the student's to sweep for this step
            StabilityResult r = stabilitySweep(*session.renderer, m, scene, source);
            int negatives = m.desc->nonNegative ? r.gpu.negativeCount : 0;
            int refBad = r.referenceNonFinite + r.referenceNegative;
            bad += r.gpu.nonFinite() + negatives + refBad;
            std::printf("%-12s %8d %8d %8d %8d %12.3g  %s\n", m.desc->id.c_str(), r.gpu.nanCount,
                        r.gpu.infCount, negatives, refBad, r.gpu.worstExcess,
                        r.firstProblem.empty() ? "-" : r.firstProblem.c_str());
        }
        std::printf(
            "(%zu extreme inputs per module; worst/tol: the largest distance outside the "
            "reference's band, in tolerances)\n",
            extremeSurfaces().labels.size());
        return bad ? 1 : 0;
    }

private:
    std::vector<std::string> ids_;
    std::string submission_;
};

class GalleryCommand : public Command {
public:
    GalleryCommand() : Command("gallery", "Render every module's default view") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("--out", outDir_, "Output folder (default: gallery)");
        cmd.add_option("--size", size_, "Image size WxH or N (default 512x512)");
    }
    int run(const GlobalOptions& global) override {
        Session session(global);
        const Size s = parseSize(size_);
        const fs::path dir = outDir_;
        fs::create_directories(dir);
        std::ofstream html(dir / "index.html");
        html << "<!doctype html><meta charset=utf-8><title>pbrlab gallery</title>"
                "<style>body{font-family:sans-serif;background:#222;color:#ddd}"
                "figure{display:inline-block;margin:8px}</style><h1>pbrlab: every step</h1>\n";
        int failures = 0;
        // One picture: rendered, written, and shown in the page under `caption`.
        auto add = [&](const LoadedModule& m, const Scene& scene, const std::string& name,
                       const std::string& caption) {
            auto r = session.renderer->renderScene(m, ParamValues(m.desc->params), scene, {},
                                                   s.width, s.height, false);
            writeOutput(*m.desc, r, dir / name);
            html << "<figure><img src=\"" << name << "\" width=256><figcaption>" << caption
                 << "</figcaption></figure>\n";
            std::cout << "wrote " << (dir / name).string() << "\n";
        };
        for (const auto& m : session.modules->modules()) {
            try {
                add(m, loadScene(session.paths.scene(m.desc->scene)),
                    findContractStep(m.desc->id)->numbered() + ".png",
                    std::to_string(m.desc->step) + ". " + m.desc->title);
            } catch (const Error& e) {
                ++failures;
                std::cerr << "error: " << m.desc->id << ": " << e.what() << "\n";
            }
        }
        // The views the steps add (step.json "gallery"): generated models, scenes placing them.
        html << "<h2>glTF models and scenes</h2>\n";
        for (const auto& m : session.modules->modules())
            for (const ContractStep::GalleryView& v : findContractStep(m.desc->id)->gallery) {
                const std::string name =
                    "model-" + m.desc->id + "-" +
                    fs::path(v.model.empty() ? v.scene : v.model).stem().string() + ".png";
                const std::string caption =
                    m.desc->id +
                    (v.model.empty() ? ", scene " + v.scene + ".json" : " on " + v.model);
                try {
                    const std::string model =
                        v.model.empty() ? ""
                                        : (session.paths.assets() / "models" / v.model).string();
                    add(m, sceneFor(session, *m.desc, v.scene, model), name, caption);
                } catch (const Error& e) {
                    ++failures;
                    std::cerr << "error: " << caption << ": " << e.what() << "\n";
                }
            }
        std::cout << "gallery: " << (dir / "index.html").string() << "\n";
        return failures ? 1 : 0;
    }

private:
    std::string outDir_ = "gallery", size_ = "512x512";
};

}  // namespace

std::unique_ptr<Command> stabilityCommand() {
    return std::make_unique<StabilityCommand>();
}
std::unique_ptr<Command> galleryCommand() {
    return std::make_unique<GalleryCommand>();
}

}  // namespace pbrlab
