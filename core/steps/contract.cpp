#include "steps/contract.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>

#include "steps/paths.h"
#include "util/error.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace pbrlab {

std::string ContractStep::numbered() const {
    char buf[8];
    std::snprintf(buf, sizeof buf, "%02d-", step);
    return buf + id;
}

namespace {

struct Contract {
    std::mutex mutex;
    std::vector<fs::path> roots;
    bool loaded = false;
    // Every contract loaded so far, the last one current: a root added later loads a new one
    // and leaves the pointers into the old ones valid.
    std::vector<std::unique_ptr<std::vector<ContractStep>>> loads;
};

Contract& contract() {
    static Contract c;
    return c;
}

// The built-in step folders: the data root's labs/ (the source tree, or share/pbrlab/labs).
fs::path builtInRoot() {
    return DataPaths::locate().labs();
}

// Letters, digits and _: what GLSL names and file stems may hold.
bool isIdChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// step.json "precompute": {"kind": "cube" | "cube_mips" | "square", "shader": "<file in the
// step folder>", "sampler": "<contract sampler>"}.
ContractStep::PrecomputePass readPrecompute(const fs::path& file, const json& j) {
    using Pass = ContractStep::PrecomputePass;
    const std::string where = file.string() + ": \"precompute\"";
    if (!j.is_object())
        throw Error(where + " must be an object with \"kind\", \"shader\" and \"sampler\"");
    auto text = [&](const char* name) {
        if (!j.contains(name) || !j.at(name).is_string() || j.at(name).get<std::string>().empty())
            throw Error(where + ": missing field \"" + name + "\" (a string)");
        return j.at(name).get<std::string>();
    };
    Pass pass;
    const std::string kind = text("kind");
    if (kind == "cube")
        pass.kind = Pass::Kind::Cube;
    else if (kind == "cube_mips")
        pass.kind = Pass::Kind::CubeMips;
    else if (kind == "square")
        pass.kind = Pass::Kind::Square;
    else
        throw Error(where + ": \"kind\" is \"" + kind + "\"; one of cube, cube_mips, square");
    const std::string shader = text("shader");
    // A file of the step's own folder, so the folder is the whole step.
    if (fs::path(shader).has_parent_path() || shader == "." || shader == "..")
        throw Error(where + ": \"shader\" must name a file in the step folder, not a path (" +
                    shader + ")");
    pass.shader = file.parent_path() / shader;
    std::error_code ec;
    if (!fs::is_regular_file(pass.shader, ec))
        throw Error(where + ": \"shader\" " + pass.shader.string() + " does not exist");
    pass.sampler = text("sampler");
    if (!std::all_of(pass.sampler.begin(), pass.sampler.end(), isIdChar))
        throw Error(where + ": \"sampler\" is not a GLSL name (" + pass.sampler + ")");
    return pass;
}

ContractStep readStep(const fs::path& file) {
    std::ifstream in(file);
    if (!in) throw Error(file.string() + ": cannot read");
    json j;
    try {
        j = json::parse(in);
    } catch (const std::exception& e) {
        throw Error(file.string() + ": not valid JSON (" + e.what() + ")");
    }
    auto field = [&](const char* name) -> const json& {
        if (!j.is_object() || !j.contains(name))
            throw Error(file.string() + ": missing field \"" + name + "\"");
        return j.at(name);
    };
    ContractStep s;
    try {
        s.id = field("id").get<std::string>();
        s.lab = field("lab").get<std::string>();
        s.order = field("order").get<double>();
        s.function = field("function").get<std::string>();
        s.calls = j.value("calls", std::vector<std::string>());
        s.hides = j.value("hides", std::vector<std::string>());
        s.provides = j.value("provides", std::vector<std::string>());
        if (j.contains("precompute")) s.precompute = readPrecompute(file, j.at("precompute"));
        if (s.precompute && std::find(s.provides.begin(), s.provides.end(),
                                      s.precompute->sampler) == s.provides.end())
            s.provides.push_back(s.precompute->sampler);
        for (const json& view : j.value("gallery", json::array())) {
            ContractStep::GalleryView v{view.value("scene", ""), view.value("model", "")};
            if (v.scene.empty() == v.model.empty())
                throw Error(file.string() +
                            ": each \"gallery\" entry names a \"scene\" or a "
                            "\"model\", one of the two");
            s.gallery.push_back(v);
        }
        for (const json& helper : j.value("helpers", json::array())) {
            ContractStep::Helper h{helper.value("function", ""), helper.value("file", "")};
            if (h.function.empty() || h.file.empty())
                throw Error(file.string() +
                            ": each \"helpers\" entry names its \"function\" (the GLSL "
                            "signature) and its \"file\" (in shaders/)");
            s.helpers.push_back(h);
        }
    } catch (const json::exception& e) {
        throw Error(file.string() + ": a field has the wrong type (" + e.what() + ")");
    }
    if (s.id.empty() || !std::all_of(s.id.begin(), s.id.end(), isIdChar))
        throw Error(file.string() + ": \"id\" must be letters, digits and _ (it names <id>.glsl)");
    if (s.lab.empty()) throw Error(file.string() + ": \"lab\" is empty");
    if (s.function.find('(') == std::string::npos)
        throw Error(file.string() + ": \"function\" is not a GLSL signature");
    s.folder = file.parent_path();
    std::error_code ec;
    s.withheld =
        !fs::exists(s.folder / "solution.glsl", ec) && fs::exists(s.folder / "starter.glsl", ec);
    return s;
}

// A hidden step is an earlier one, and nothing this step's programs link calls it: its own
// calls, or any earlier step's reference solution.
void checkHides(const std::vector<ContractStep>& steps) {
    for (const ContractStep& s : steps)
        for (const std::string& hidden : s.hides) {
            const std::string file = (s.folder / "step.json").string();
            auto found = std::find_if(steps.begin(), steps.end(),
                                      [&](const ContractStep& t) { return t.id == hidden; });
            if (found == steps.end() || found->order >= s.order)
                throw Error(file + ": hides '" + hidden + "', which is no earlier step");
            for (const ContractStep& t : steps) {
                if (t.order > s.order || t.id == hidden) continue;
                if (std::find(t.calls.begin(), t.calls.end(), hidden) != t.calls.end())
                    throw Error(file + ": hides '" + hidden + "', which " + t.id +
                                " calls (its program needs it)");
            }
        }
}

}  // namespace

std::vector<ContractStep> readStepFolders(const std::vector<fs::path>& roots) {
    std::vector<ContractStep> steps;
    for (const fs::path& root : roots) {
        std::error_code ec;
        if (!fs::is_directory(root, ec)) continue;
        std::vector<fs::path> files;
        for (const auto& entry : fs::directory_iterator(root, ec))
            if (fs::is_regular_file(entry.path() / "step.json", ec))
                files.push_back(entry.path() / "step.json");
        std::sort(files.begin(), files.end());
        for (const fs::path& file : files) {
            ContractStep s = readStep(file);
            auto same = std::find_if(steps.begin(), steps.end(),
                                     [&](const ContractStep& t) { return t.id == s.id; });
            if (same == steps.end()) {
                steps.push_back(std::move(s));
            } else if (!fs::equivalent(same->folder, s.folder, ec)) {
                throw Error(file.string() + ": step id '" + s.id + "' is already declared by " +
                            (same->folder / "step.json").string());
            }
        }
    }
    std::stable_sort(steps.begin(), steps.end(), [](const ContractStep& a, const ContractStep& b) {
        return a.order < b.order;
    });
    for (size_t i = 0; i < steps.size(); ++i) {
        steps[i].step = int(i + 1);
        if (i > 0 && steps[i].order == steps[i - 1].order) {
            char order[32];
            std::snprintf(order, sizeof order, "%g", steps[i].order);
            throw Error((steps[i].folder / "step.json").string() + ": order " + order +
                        " is also " + steps[i - 1].id + "'s: give each step its own");
        }
    }
    // A contract function is declared from its step on in every later program: one name, one
    // step.
    for (size_t i = 0; i < steps.size(); ++i)
        for (size_t k = 0; k < i; ++k)
            if (functionName(steps[i].function) == functionName(steps[k].function))
                throw Error((steps[i].folder / "step.json").string() + ": function " +
                            functionName(steps[i].function) + " is already " + steps[k].id + "'s");
    checkHides(steps);
    // The programs concatenate the steps' files in order: a step may call earlier ones only.
    for (const ContractStep& s : steps)
        for (const std::string& callee : s.calls) {
            auto found = std::find_if(steps.begin(), steps.end(),
                                      [&](const ContractStep& t) { return t.id == callee; });
            if (found == steps.end())
                throw Error((s.folder / "step.json").string() + ": calls '" + callee +
                            "', which no step folder declares");
            if (found->order >= s.order)
                throw Error((s.folder / "step.json").string() + ": calls '" + callee +
                            "', which comes after it (give this step a larger order)");
        }
    return steps;
}

namespace {

void load(Contract& c) {
    std::vector<fs::path> roots = {builtInRoot()};
    roots.insert(roots.end(), c.roots.begin(), c.roots.end());
    c.loads.push_back(std::make_unique<std::vector<ContractStep>>(readStepFolders(roots)));
    c.loaded = true;
}

}  // namespace

void addStepRoot(const fs::path& root) {
    Contract& c = contract();
    std::lock_guard lock(c.mutex);
    std::error_code ec;
    for (const fs::path& known : c.roots)
        if (known == root || fs::equivalent(known, root, ec)) return;
    c.roots.push_back(root);
    // Only a root with step folders changes the contract (the build's modules/ folder has none).
    for (const auto& entry : fs::directory_iterator(root, ec))
        if (fs::is_regular_file(entry.path() / "step.json", ec)) {
            c.loaded = false;
            return;
        }
}

const std::vector<ContractStep>& contractSteps() {
    Contract& c = contract();
    std::lock_guard lock(c.mutex);
    if (!c.loaded) load(c);
    return *c.loads.back();
}

std::vector<ContractHelper> contractHelpers() {
    std::vector<ContractHelper> helpers;
    for (const ContractStep& s : contractSteps())
        for (const ContractStep::Helper& h : s.helpers)
            helpers.push_back({h.function, h.file, s.id});
    return helpers;
}

std::string functionName(const std::string& signature) {
    std::string head = signature.substr(0, signature.find('('));
    head.erase(head.find_last_not_of(" \t") + 1);
    return head.substr(head.find_last_of(" \t") + 1);  // npos + 1 = 0: no return type
}

std::vector<const ContractStep*> stepsVisibleFrom(const ContractStep& step) {
    std::vector<const ContractStep*> visible;
    for (const ContractStep& s : contractSteps())
        if (s.step <= step.step &&
            std::find(step.hides.begin(), step.hides.end(), s.id) == step.hides.end())
            visible.push_back(&s);
    return visible;
}

std::map<std::string, std::string> unreachableFrom(const ContractStep& step) {
    std::map<std::string, std::string> names;
    auto add = [&](const std::string& signature, const ContractStep& introducer) {
        const std::string name = functionName(signature);
        names[name] = name + " is introduced in step " + std::to_string(introducer.step) + " (" +
                      introducer.id + "); " + step.id +
                      " cannot call it: a step's file may call the contract functions of its "
                      "own and earlier steps only";
    };
    for (const ContractStep& s : contractSteps()) {
        if (s.step <= step.step) continue;
        add(s.function, s);
        for (const ContractStep::Helper& h : s.helpers) add(h.function, s);
    }
    for (const std::string& hidden : step.hides)
        if (const ContractStep* s = findContractStep(hidden)) {
            const std::string name = functionName(s->function);
            names[name] = name + " (step " + std::to_string(s->step) + ", " + s->id +
                          ") computes what " + step.id + " asks for another way; " + step.id +
                          " cannot call it: write the step's own method";
        }
    return names;
}

const ContractStep* findProvider(const std::string& sampler) {
    for (const auto& s : contractSteps())
        for (const std::string& provided : s.provides)
            if (provided == sampler) return &s;
    return nullptr;
}

const ContractStep* findContractStep(const std::string& id) {
    for (const auto& s : contractSteps())
        if (s.id == id) return &s;
    return nullptr;
}

namespace {

std::mutex withheldMutex;
fs::path withheldFolder;

}  // namespace

bool solutionWithheld(const ContractStep& step) {
    return step.withheld;
}

void setWithheldStepsFolder(const fs::path& folder) {
    std::lock_guard lock(withheldMutex);
    withheldFolder = folder;
}

fs::path withheldStepsFolder() {
    std::lock_guard lock(withheldMutex);
    return withheldFolder;
}

fs::path referenceImplementation(const ContractStep& step) {
    if (!solutionWithheld(step)) return step.folder / "solution.glsl";
    const fs::path folder = withheldStepsFolder();
    std::error_code ec;
    if (!folder.empty() && fs::exists(folder / (step.id + ".glsl"), ec))
        return folder / (step.id + ".glsl");
    return step.folder / "starter.glsl";
}

std::vector<const ContractStep*> contractClosure(const std::string& id,
                                                 const std::vector<std::string>& extra) {
    const ContractStep* self = findContractStep(id);
    if (!self) throw Error("'" + id + "' is not a contract step id");
    std::set<int> wanted;
    std::vector<std::string> pending = extra;
    pending.push_back(id);
    for (const auto& s : contractSteps())
        if (s.lab == self->lab && s.step < self->step) pending.push_back(s.id);
    while (!pending.empty()) {
        std::string next = pending.back();
        pending.pop_back();
        const ContractStep* s = findContractStep(next);
        if (!s) throw Error("'" + next + "' is not a contract step id");
        if (!wanted.insert(s->step).second) continue;
        pending.insert(pending.end(), s->calls.begin(), s->calls.end());
    }
    std::vector<const ContractStep*> result;
    for (const auto& s : contractSteps())
        if (wanted.count(s.step)) result.push_back(&s);
    return result;
}

}  // namespace pbrlab
