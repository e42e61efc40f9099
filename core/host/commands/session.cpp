#include "session.h"

#include <cstdio>
#include <iostream>
#include <sstream>

#include "native/huge_pages.h"
#include "render/display.h"
#include "steps/contract.h"
#include "util/error.h"
#include "util/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

std::vector<fs::path> modulesDirs(const GlobalOptions& global) {
    return moduleDirs(std::vector<fs::path>(global.modulesDirs.begin(), global.modulesDirs.end()));
}

void printPrecomputePass(const std::string& pass) {
    std::cerr << "precompute " << pass << "\n";
}

Session::Session(const GlobalOptions& global, bool needGl, const std::string& onlyId) {
    modules = std::make_unique<ModuleRegistry>(modulesDirs(global), onlyId);
    for (const auto& f : modules->failures())
        std::cerr << "warning: module " << f.library.string() << " not loaded: " << f.reason
                  << "\n";
    if (!needGl) return;
    context = createHeadlessContext();
    logLine("gl", context->description());
    RendererOptions options;
    options.onPrecomputePass = printPrecomputePass;
    renderer = std::make_unique<LabRenderer>(paths, options);
}

Size parseSize(const std::string& text, const std::string& option) {
    Size s;
    std::istringstream in(text);
    bool read = bool(in >> s.width);
    if (read && in.eof()) {
        s.height = s.width;  // "N": a square
    } else {
        char x = 0;
        read = read && (in >> x >> s.height) && x == 'x' && in.eof();
    }
    if (!read || s.width < 2 || s.height < 2 || s.width > 8192 || s.height > 8192)
        throw Error(option + " " + text + ": expected WxH or N, e.g. 512x512 or 512 (2..8192)");
    return s;
}

int parseSquareSize(const std::string& text) {
    const Size s = parseSize(text);
    if (s.width != s.height) throw Error("--size " + text + ": this command renders a square");
    return s.width;
}

ParamValues parseSets(const ModuleDesc& m, const std::vector<std::string>& sets) {
    ParamValues values(m.params);
    for (const auto& s : sets) applyAssignment(m.params, values, s);
    return values;
}

StudentSource studentSource(const std::string& dir, bool cumulative, const std::string& id) {
    StudentSource s{dir, cumulative};
    if (!dir.empty()) {
        // Over an assignment site's step folders (PBRLAB_DATA), the withheld steps' functions
        // come from the submission, as the page takes them from its workspace (contract.h).
        setWithheldStepsFolder(dir);
        if (!fs::is_directory(dir)) throw Error("--submission " + dir + ": not a directory");
        if (!fs::exists(fs::path(dir) / (id + ".glsl")))
            std::cerr << "note: " << (fs::path(dir) / (id + ".glsl")).string()
                      << " does not exist; using the reference solution\n";
    }
    return s;
}

void writeOutput(const ModuleDesc& m, const RenderResult& r, const fs::path& out) {
    std::string ext = out.extension().string();
    if (ext == ".exr") {
        writeImage(out, r.value, FileDepth::Float32);
    } else if (ext == ".png") {
        writeImage(out, displayImage(r.value, m.display, m.components), FileDepth::Uint8, true);
    } else {
        throw Error("--out " + out.string() + ": use a .png (display) or .exr (linear) file");
    }
}

Scene sceneFor(const Session& session, const ModuleDesc& m, const std::string& sceneName,
               const std::string& model) {
    Scene scene = loadScene(session.paths.scene(sceneName.empty() ? m.scene : sceneName));
    if (!model.empty()) scene = sceneForModel(scene, model);
    for (const auto& model : scene.models)
        for (const auto& w : model.data->warnings)
            std::cerr << "note: " << model.data->file.string() << ": " << w << "\n";
    return scene;
}

void printStats(const Session& session) {
    for (int c = 0; c < int(Counter::Count); ++c)
        std::cout << counterName(Counter(c)) << ": " << eventCount(Counter(c)) << "\n";
    std::cout << "memory pages: " << memoryPagesDescription() << "\n";
    if (session.renderer)
        for (const CompiledProgram& p : session.renderer->programs().compiled())
            std::printf("  program %-30s {%s} %.1f ms\n", p.label.c_str(), p.defines.c_str(),
                        p.milliseconds);
    std::cout << journal();
}

}  // namespace pbrlab
