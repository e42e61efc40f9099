#include "course/kit.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "steps/contract.h"
#include "steps/solution_stub.h"
#include "util/error.h"
#include "util/fs.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

void writeFile(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream out(p, std::ios::binary);
    out << text;
    if (!out) throw Error(p.string() + ": cannot write");
}

}  // namespace

int writeKit(const ModuleRegistry& modules, const KitOptions& o) {
    std::error_code ec;
    if (fs::exists(o.out, ec) && !fs::is_empty(o.out, ec) && !o.force)
        throw Error(o.out.string() + " is not empty; use --force to write into it anyway");
    int releaseStep = 0;
    if (!o.releaseThrough.empty()) {
        const ContractStep* s = findContractStep(o.releaseThrough);
        if (!s) throw Error("--release-through " + o.releaseThrough + ": not a module id");
        releaseStep = s->step;
    }
    int written = 0;
    std::string list;
    for (const LoadedModule& m : modules.modules()) {
        const ModuleDesc& d = *m.desc;
        if (!o.steps.empty() && std::find(o.steps.begin(), o.steps.end(), d.id) == o.steps.end())
            continue;
        fs::path solution = m.sourceDir / "solution.glsl";
        std::string text = readFile(solution);
        bool released = o.withSolutions || d.step <= releaseStep;
        writeFile(o.out / (d.id + ".glsl"),
                  released ? text : stubSolution(text, d.function, solution.string()));
        fs::path handout = m.sourceDir / "README.md";
        if (fs::exists(handout))
            writeFile(o.out / "handouts" / (findContractStep(d.id)->numbered() + ".md"),
                      readFile(handout));
        list += "| " + std::to_string(d.step) + " | `" + d.id + ".glsl` | `" + d.function + "` | " +
                (released ? "solution given" : "to write") + " |\n";
        ++written;
    }
    writeFile(o.out / "README.md",
              "# pbrlab kit\n\n"
              "One file per step. Write the body of each function where the TODO is; you may "
              "add helper functions of your own above it (do not name them `pbrlab_*`, and do "
              "not define `PI`: it is provided, as are `NUM_LIGHTS`, `uLightPositions`, "
              "`uLightColors` and the contract functions of the earlier steps). The "
              "handouts "
              "in `handouts/` explain each step.\n\n" +
                  (o.due.empty() ? std::string() : "Due: " + o.due + "\n\n") +
                  "| step | file | function | status |\n|---|---|---|---|\n" + list +
                  "\n## Run and test\n\n"
                  "    pbrlab gui                      # from this folder: live view, hot reload\n"
                  "    pbrlab check ndotl --submission .   # grade one step, every check printed\n"
                  "    pbrlab render ndotl --submission . --out ndotl.png\n"
                  "    pbrlab grade .                  # every step, as the autograder does\n");
    return written;
}

std::vector<std::string> writeSiteSteps(const ModuleRegistry& modules, const KitOptions& o) {
    std::error_code ec;
    if (fs::exists(o.out, ec) && !fs::is_empty(o.out, ec) && !o.force)
        throw Error(o.out.string() + " is not empty; use --force to write into it anyway");
    const ContractStep* released =
        o.releaseThrough.empty() ? nullptr : findContractStep(o.releaseThrough);
    if (!o.releaseThrough.empty() && !released)
        throw Error("--release-through " + o.releaseThrough + ": not a module id");
    auto handedOut = [&](const std::string& id) {
        return o.steps.empty() || std::find(o.steps.begin(), o.steps.end(), id) != o.steps.end();
    };
    int last = 0;  // the last step the kit hands out
    for (const LoadedModule& m : modules.modules())
        if (handedOut(m.desc->id)) last = std::max(last, m.desc->step);
    std::vector<std::string> withheld;
    for (const LoadedModule& m : modules.modules()) {
        const ModuleDesc& d = *m.desc;
        if (d.step > last) continue;
        const bool withhold =
            handedOut(d.id) && !o.withSolutions && (!released || d.step > released->step);
        const fs::path folder = o.out / d.id;
        fs::create_directories(folder);
        for (const auto& entry : fs::recursive_directory_iterator(m.sourceDir)) {
            const fs::path relative = fs::relative(entry.path(), m.sourceDir);
            const std::string first = relative.begin()->string();
            if (withhold &&
                (first == "solution.glsl" || first == "mistakes" || first == "variants" ||
                 first == "module.cpp" || first == "CMakeLists.txt"))
                continue;
            if (entry.is_directory())
                fs::create_directories(folder / relative);
            else
                writeFile(folder / relative, readFile(entry.path()));
        }
        if (withhold) {
            const fs::path solution = m.sourceDir / "solution.glsl";
            writeFile(folder / "starter.glsl",
                      stubSolution(readFile(solution), d.function, solution.string()));
            withheld.push_back(d.id);
        }
    }
    return withheld;
}

}  // namespace pbrlab
