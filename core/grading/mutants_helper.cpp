#include "grading/mutants_helper.h"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "steps/contract.h"
#include "util/error.h"
#include "util/fs.h"

namespace fs = std::filesystem;

namespace pbrlab {

std::string VisibleFunction::signature() const {
    std::string s = returnType + " " + name + "(";
    for (size_t i = 0; i < parameterTypes.size(); ++i) s += (i ? ", " : "") + parameterTypes[i];
    return s + ")";
}

namespace {

// The types and names of a parameter list ("float cosTheta, in vec3 F0"), qualifiers left out.
void parseParameters(const std::string& list, std::vector<std::string>* types,
                     std::vector<std::string>* names) {
    static const std::set<std::string> qualifiers = {"in",    "out",     "inout", "const",
                                                     "highp", "mediump", "lowp"};
    std::istringstream params(list);
    for (std::string param; std::getline(params, param, ',');) {
        std::istringstream words(param);
        std::vector<std::string> w;
        for (std::string word; words >> word;)
            if (!qualifiers.count(word)) w.push_back(word);
        if (w.empty() || (w.size() == 1 && w[0] == "void")) continue;
        types->push_back(w[0]);
        names->push_back(w.size() > 1 ? w[1] : "");
    }
}

// A function's signature on one line of the host's code (how every host file writes it).
bool parseFunction(const std::string& line, VisibleFunction* f) {
    static const std::regex function(R"(^\s*(\w+)\s+(\w+)\s*\(([^)]*)\)\s*(;|\{|$))");
    static const std::set<std::string> notTypes = {"return", "else", "if", "for", "while"};
    std::smatch m;
    if (!std::regex_search(line, m, function) || notTypes.count(m[1].str())) return false;
    f->returnType = m[1].str();
    f->name = m[2].str();
    parseParameters(m[3].str(), &f->parameterTypes, &f->parameterNames);
    return true;
}

// A student's folder for one step, removed with the object.
struct TempKit {
    fs::path dir;
    explicit TempKit(const std::string& id) {
        dir = fs::temp_directory_path() /
              ("pbrlab-reach-" + id + "-" + std::to_string(::getpid()) + "-" +
               std::to_string(reinterpret_cast<std::uintptr_t>(this)));
        fs::create_directories(dir);
    }
    ~TempKit() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
};

bool isBuiltInType(const std::string& type) {
    static const std::regex builtIn(R"((float|int|uint|bool|[iub]?vec[234]|mat[234]))");
    return std::regex_match(type, builtIn);
}

// 0 and 1 of a built-in type, as GLSL literals ("vec3(0.0)", "1u").
std::vector<std::string> constantsOf(const std::string& type) {
    if (type == "float") return {"0.0", "1.0"};
    if (type == "int") return {"0", "1"};
    if (type == "uint") return {"0u", "1u"};
    if (type == "bool") return {"false", "true"};
    if (type.rfind("uvec", 0) == 0) return {type + "(0u)", type + "(1u)"};
    if (type.rfind("ivec", 0) == 0 || type.rfind("bvec", 0) == 0)
        return {type + "(0)", type + "(1)"};
    return {type + "(0.0)", type + "(1.0)"};
}

}  // namespace

VisibleNames namesVisibleToStudent(LabRenderer& renderer, const LoadedModule& module) {
    const std::string& id = module.desc->id;
    TempKit kit(id);
    {
        std::ofstream out(kit.dir / (id + ".glsl"), std::ios::binary);
        out << readFile(module.sourceDir / "solution.glsl");
    }
    const ProgramRecipe recipe = renderer.viewRecipe(module, {kit.dir}, true, 1);
    const ExpandedShader program =
        renderer.programs().preprocessor().expand(recipe.fragment, recipe.defines);
    if (program.studentTexts.size() != 1)
        throw Error(id + ": the view program holds " + std::to_string(program.studentTexts.size()) +
                    " student's parts, not one");
    const int student = program.studentTexts.begin()->first;

    VisibleNames names;
    std::set<std::string> seen, macros;
    static const std::regex marker(R"(^#line \d+ (\d+)$)");
    static const std::regex define(R"(^\s*#\s*define\s+(\w+))");
    static const std::regex undef(R"(^\s*#\s*undef\s+(\w+))");
    int source = -1;
    bool before = true;
    std::istringstream in(program.text);
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (std::regex_match(line, m, marker)) {
            source = std::stoi(m[1].str());
            before = before && source != student;
            continue;
        }
        if (source == student) continue;  // the student's own text and the #undefs after it
        if (before && std::regex_search(line, m, define)) macros.insert(m[1].str());
        if (before && std::regex_search(line, m, undef)) macros.erase(m[1].str());
        VisibleFunction f;
        if (!parseFunction(line, &f) || !seen.insert(f.signature()).second) continue;
        f.afterStudent = !before;
        f.source = source >= 0 && size_t(source) < program.sourceNames.size()
                       ? program.sourceNames[size_t(source)]
                       : "<program>";
        names.functions.push_back(f);
    }
    // The defines the host writes first (before any #line marker) are macros too.
    for (const auto& [name, value] : recipe.defines) macros.insert(name);
    names.macros.assign(macros.begin(), macros.end());
    return names;
}

std::vector<Mutant> helperCallMutants(LabRenderer& renderer, const LoadedModule& module) {
    const ContractStep* step = findContractStep(module.desc->id);
    if (!step) throw Error("'" + module.desc->id + "' is not a contract step id");
    VisibleFunction own;
    if (!parseFunction(step->function, &own))
        throw Error(step->id + ": cannot read the signature " + step->function);

    std::vector<Mutant> mutants;
    for (const VisibleFunction& f : namesVisibleToStudent(renderer, module).functions) {
        if (f.returnType != own.returnType || f.name == own.name) continue;
        if (!std::all_of(f.parameterTypes.begin(), f.parameterTypes.end(), isBuiltInType))
            continue;  // a type declared after the student's part: no student can call it
        // Candidates per parameter: the step's argument of that name and type, else the next
        // unused one of that type, else 0; then 0, 1 and the step's other arguments of the type.
        std::vector<bool> used(own.parameterTypes.size(), false);
        std::vector<std::vector<std::string>> candidates(f.parameterTypes.size());
        auto take = [&](size_t k) {
            used[k] = true;
            return own.parameterNames[k];
        };
        for (size_t i = 0; i < f.parameterTypes.size(); ++i) {
            const std::string& type = f.parameterTypes[i];
            std::string mapped;
            for (size_t k = 0; k < own.parameterTypes.size() && mapped.empty(); ++k)
                if (!used[k] && own.parameterTypes[k] == type &&
                    own.parameterNames[k] == f.parameterNames[i])
                    mapped = take(k);
            for (size_t k = 0; k < own.parameterTypes.size() && mapped.empty(); ++k)
                if (!used[k] && own.parameterTypes[k] == type) mapped = take(k);
            std::vector<std::string>& c = candidates[i];
            if (!mapped.empty()) c.push_back(mapped);
            for (const std::string& constant : constantsOf(type)) c.push_back(constant);
            for (size_t k = 0; k < own.parameterTypes.size(); ++k)
                if (own.parameterTypes[k] == type &&
                    std::find(c.begin(), c.end(), own.parameterNames[k]) == c.end())
                    c.push_back(own.parameterNames[k]);
        }
        // The mapped call, then one argument changed at a time.
        std::vector<std::vector<std::string>> calls;
        std::vector<std::string> base;
        for (const auto& c : candidates) base.push_back(c.front());
        calls.push_back(base);
        for (size_t i = 0; i < candidates.size(); ++i)
            for (size_t j = 1; j < candidates[i].size(); ++j) {
                std::vector<std::string> call = base;
                call[i] = candidates[i][j];
                calls.push_back(call);
            }
        constexpr size_t kCallsPerFunction = 6;
        if (calls.size() > kCallsPerFunction) calls.resize(kCallsPerFunction);
        for (const auto& args : calls) {
            std::string call = f.name + "(";
            for (size_t i = 0; i < args.size(); ++i) call += (i ? ", " : "") + args[i];
            call += ")";
            Mutant m;
            m.family = "helper";
            m.description = "returns " + call + " (" + f.source + ")";
            m.change = "`return " + call + ";` for the step's own computation";
            m.text = "// " + m.family + " mutant: " + m.description + "\n" +
                     (f.afterStudent ? f.signature() + ";\n" : "") + step->function +
                     "\n{\n    return " + call + ";\n}\n";
            mutants.push_back(m);
        }
    }
    return mutants;
}

}  // namespace pbrlab
