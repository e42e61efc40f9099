// What the commands share: the services a rendering command starts, and the readers of the
// options they have in common (--size, --set, --submission, --scene/--model, --out).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "command.h"
#include "gl/context.h"
#include "render/renderer.h"
#include "steps/paths.h"
#include "steps/plugin_host.h"

namespace pbrlab {

// The module folders: the built-in ones, $PBRLAB_MODULES, then --modules.
std::vector<std::filesystem::path> modulesDirs(const GlobalOptions& global);

// Progress of the precompute passes, on stderr.
void printPrecomputePass(const std::string& pass);

// What every command that renders needs, made in the right order (context before GL use).
struct Session {
    std::unique_ptr<GlContext> context;
    DataPaths paths = DataPaths::locate();
    std::unique_ptr<ModuleRegistry> modules;
    std::unique_ptr<LabRenderer> renderer;

    // `onlyId`: the command is about that one module (see ModuleRegistry).
    explicit Session(const GlobalOptions& global, bool needGl = true,
                     const std::string& onlyId = {});
};

struct Size {
    int width = 512, height = 512;
};

// --size: "WxH", or "N" for N x N; each side 2..8192. `option` names it in the error.
Size parseSize(const std::string& text, const std::string& option = "--size");
// The same for a square (--size of check, converge, textures): its side.
int parseSquareSize(const std::string& text);

// --set name=value, each in turn, over the module's defaults.
ParamValues parseSets(const ModuleDesc& m, const std::vector<std::string>& sets);

// --submission DIR (may be empty: the reference solutions), with a note when it lacks <id>.glsl.
StudentSource studentSource(const std::string& dir, bool cumulative, const std::string& id);

// --out: a .png (display-encoded) or .exr (linear values).
void writeOutput(const ModuleDesc& m, const RenderResult& r, const std::filesystem::path& out);

// The scene a command renders: --model frames a glTF model lit like the module's (or
// --scene's) scene; otherwise --scene, else the module's own scene.
Scene sceneFor(const Session& session, const ModuleDesc& m, const std::string& sceneName,
               const std::string& model);

// What the run loaded, compiled and precomputed, with times (--stats).
void printStats(const Session& session);

// The descriptions of the options that mean the same in every command.
namespace help {
inline constexpr const char* step = "Step id (see `pbrlab list`)";
inline constexpr const char* steps = "Step ids (default: all)";
inline constexpr const char* submission =
    "Folder with the student's <id>.glsl files (default: the reference solutions)";
inline constexpr const char* cumulative =
    "Also use the student's files for the other steps (default: stepwise)";
inline constexpr const char* set = "Parameter name=value (repeatable)";
inline constexpr const char* scene = "Scene name in assets/scenes or a .json file";
inline constexpr const char* model =
    "A glTF model (.glb/.gltf) to view instead, framed and lit like the scene";
inline constexpr const char* stats =
    "Print what was compiled (each permutation), loaded and precomputed, with times";
inline constexpr const char* seed = "Seed of the random domain points (default 1)";
inline constexpr const char* sunEnvironment =
    "The environment with a sun that the steps reading the environment are also graded on: "
    "a generated one's name or an .hdr/.exr file, such as a real sky (default: each step's, "
    "sky-sun)";
}  // namespace help

}  // namespace pbrlab
