#include "shader/preprocess.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "shader/code_facts.h"
#include "shader/student_file.h"
#include "util/error.h"
#include "util/fs.h"

namespace fs = std::filesystem;

namespace pbrlab {

ShaderPreprocessor::ShaderPreprocessor(std::vector<fs::path> roots, GlslDialect dialect)
    : roots_(std::move(roots)), dialect_(dialect) {}

namespace {

// GlslDialect::Es300's header. The built-ins' replacements are exact: a swap network for the
// bit reversal, a binary search for the most significant bit (of ~x for a negative int, as
// GLSL 4.00 defines it).
const char* const kEs300Header = R"(#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp samplerCube;
precision highp sampler3D;
precision highp sampler2DArray;
uint bitfieldReverse(uint x) {
    x = ((x & 0x55555555u) << 1u) | ((x >> 1u) & 0x55555555u);
    x = ((x & 0x33333333u) << 2u) | ((x >> 2u) & 0x33333333u);
    x = ((x & 0x0F0F0F0Fu) << 4u) | ((x >> 4u) & 0x0F0F0F0Fu);
    x = ((x & 0x00FF00FFu) << 8u) | ((x >> 8u) & 0x00FF00FFu);
    return (x << 16u) | (x >> 16u);
}
int bitfieldReverse(int x) { return int(bitfieldReverse(uint(x))); }
int findMSB(uint x) {
    if (x == 0u) return -1;
    int n = 0;
    for (int s = 16; s > 0; s >>= 1)
        if (x >= (1u << uint(s))) {
            x >>= uint(s);
            n += s;
        }
    return n;
}
int findMSB(int x) { return findMSB(uint(x < 0 ? ~x : x)); }
)";

// Built-ins with cases GLSL leaves undefined that a student's code reaches, defined the same on
// every GPU so that a grade does not depend on the driver. Each student's part reads them
// through a macro of the built-in's name (see expand). pow of a negative base is NaN, which is
// what Mesa (the desktop's grader) computes; SwiftShader (the browser's) gives a number, so a
// Fresnel term without its clamp passed in the page and failed on the desktop.
const char* const kDefinedBuiltins = R"(float pbrlab_definedPow(float x, float y) {
    return x < 0.0 ? intBitsToFloat(0x7fc00000) : pow(x, y);
}
vec2 pbrlab_definedPow(vec2 x, vec2 y) {
    return mix(pow(x, y), vec2(intBitsToFloat(0x7fc00000)), lessThan(x, vec2(0.0)));
}
vec3 pbrlab_definedPow(vec3 x, vec3 y) {
    return mix(pow(x, y), vec3(intBitsToFloat(0x7fc00000)), lessThan(x, vec3(0.0)));
}
vec4 pbrlab_definedPow(vec4 x, vec4 y) {
    return mix(pow(x, y), vec4(intBitsToFloat(0x7fc00000)), lessThan(x, vec4(0.0)));
}
)";

// The diagnosis build's functions (kTraceNonFinite): one per traced built-in and argument
// type, calling the built-in (pow: its defined form); a non-finite result of finite arguments
// is noted and replaced by 0, so that whether the value is finite after it says whether the
// NaN or Inf the student sees came from those calls.
std::string traceFunctions() {
    std::string out = R"(int pbrlab_traceSite = 0;
int pbrlab_traceOther = 0;
bool pbrlab_finite(float x) { return !isnan(x) && !isinf(x); }
bool pbrlab_finite(vec2 x) { return !any(isnan(x)) && !any(isinf(x)); }
bool pbrlab_finite(vec3 x) { return !any(isnan(x)) && !any(isinf(x)); }
bool pbrlab_finite(vec4 x) { return !any(isnan(x)) && !any(isinf(x)); }
void pbrlab_noteCall(int call, int line) {
    int site = (abs(call) * 65536 + min(line, 65535)) * (call < 0 ? -1 : 1);
    if (pbrlab_traceSite == 0) pbrlab_traceSite = site;
    else if (site != pbrlab_traceSite && pbrlab_traceOther == 0) pbrlab_traceOther = site;
}
bool pbrlab_powUndefined(float x, float y) { return x < 0.0 || (x == 0.0 && y <= 0.0); }
)";
    for (const char* t : {"vec2", "vec3", "vec4"}) {
        const std::string T = t;
        out += "bool pbrlab_powUndefined(" + T + " x, " + T + " y) {\n    return any(lessThan(x, " +
               T + "(0.0))) ||\n           any(greaterThan(" + T + "(equal(x, " + T + "(0.0))) * " +
               T + "(lessThanEqual(y, " + T + "(0.0))), " + T + "(0.0)));\n}\n";
    }
    const std::vector<TracedCall>& calls = tracedCalls();
    for (size_t k = 0; k < calls.size(); ++k) {
        const TracedCall& c = calls[k];
        const std::string impl = c.builtin == "pow" ? "pbrlab_definedPow" : c.builtin;
        const std::string index = std::to_string(k + 1);
        // The overflow case where the arguments lie where the built-in is defined.
        const std::string code =
            c.overflow.empty() ? index : "pbrlab_powUndefined(x, y) ? " + index + " : -" + index;
        for (const char* t : {"float", "vec2", "vec3", "vec4"}) {
            const std::string T = t;
            // mod(genType, float) too.
            for (const std::string& second : c.arguments == 2 && T != "float" && c.builtin == "mod"
                                                 ? std::vector<std::string>{T, "float"}
                                                 : std::vector<std::string>{T}) {
                const bool two = c.arguments == 2;
                out += T + " pbrlab_trace_" + c.builtin + "(" + T + " x, " +
                       (two ? second + " y, " : "") + "int line) {\n    " + T + " r = " + impl +
                       (two ? "(x, y);\n" : "(x);\n") + "    if (pbrlab_finite(x) && " +
                       (two ? "pbrlab_finite(y) && " : "") + "!pbrlab_finite(r)) {\n" +
                       "        pbrlab_noteCall(" + code + ", line);\n        return " + T +
                       "(0.0);\n    }\n    return r;\n}\n";
            }
        }
    }
    return out;
}

}  // namespace

namespace {

std::string readText(const fs::path& path) {
    std::string text = readFile(path);
    // GL reads the source as a C string: a NUL would silently cut the program short there.
    if (text.find('\0') != std::string::npos)
        throw Error(path.string() + ": contains NUL bytes (not text): refused");
    return text;
}

// A logical line of a student's file as the compiler reads it: line continuations joined and
// comments left out (each replaced by a space), with the file's line of each character.
struct CodeLine {
    std::string code;
    std::vector<int> lines;
    int lineAt(size_t i) const { return lines.empty() ? 0 : lines[std::min(i, lines.size() - 1)]; }
};

// The file's logical lines, in order; `openComment` gets the line of a /* left open at the
// end (0 when none). Continuations are joined before comments are found, as the compiler
// does, so a name hidden by `*\` + newline + `/` is seen where the compiler sees it.
std::vector<CodeLine> codeLines(const std::string& text, int* openComment) {
    // Continuations joined first, each character keeping the line it was on.
    std::string joined;
    std::vector<int> lineOf;
    for (size_t i = 0, line = 1; i < text.size(); ++i) {
        if (text[i] == '\\' &&
            (text.compare(i + 1, 1, "\n") == 0 || text.compare(i + 1, 2, "\r\n") == 0)) {
            i += text[i + 1] == '\r' ? 2 : 1;
            ++line;
            continue;
        }
        joined += text[i];
        lineOf.push_back(int(line));
        if (text[i] == '\n') ++line;
    }
    std::vector<CodeLine> result(1);
    int commentStart = 0;
    bool block = false, lineComment = false;
    for (size_t i = 0; i < joined.size(); ++i) {
        const char c = joined[i];
        const char next = i + 1 < joined.size() ? joined[i + 1] : '\0';
        if (c == '\n') {
            lineComment = false;
            if (!block) result.emplace_back();
        } else if (lineComment) {
            continue;  // up to the end of the line
        } else if (block) {
            if (c == '*' && next == '/') {
                block = false;
                ++i;
                result.back().code += ' ';
                result.back().lines.push_back(lineOf[i]);
            }
        } else if (c == '/' && (next == '/' || next == '*')) {
            (next == '/' ? lineComment : block) = true;
            commentStart = lineOf[i];
            ++i;
        } else {
            result.back().code += c;
            result.back().lines.push_back(lineOf[i]);
        }
    }
    *openComment = block ? commentStart : 0;
    return result;
}

// Calls f(identifier, its offset) for each identifier of a line of code (a letter or _, then
// letters, digits and _; a number's suffix, as in 1e5 or 2u, is part of the number).
template <class F>
void forEachIdentifier(const std::string& code, F f) {
    auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (size_t i = 0; i < code.size();) {
        if (!word(code[i])) {
            ++i;
            continue;
        }
        size_t end = i;
        while (end < code.size() && word(code[end])) ++end;
        if (!std::isdigit(static_cast<unsigned char>(code[i]))) f(code.substr(i, end - i), i);
        i = end;
    }
}

// The names of the functions a host file defines: a return type and a name at the start of a
// line (column 0), then `(`, and the body's `{` on that line or the signature going on after it
// (not a prototype's `;`). The host's files are written that way.
std::vector<std::string> definedFunctions(const std::string& text) {
    static const std::regex definition(R"(^(\w+)\s+(\w+)\s*\((?:[^)]*\)\s*\{.*|[^;]*)$)");
    std::vector<std::string> names;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        // Only lines that can start a definition reach the (slow) regular expression.
        if (line.empty() || !std::isalpha(static_cast<unsigned char>(line[0])) ||
            line.find('(') == std::string::npos)
            continue;
        std::smatch m;
        if (std::regex_search(line, m, definition)) names.push_back(m[2].str());
    }
    return names;
}

struct Expander {
    std::vector<fs::path> roots;
    fs::path studentFolder;  // set while expanding a student's file (see ShaderPart)
    ExpandedShader out;
    std::set<fs::path> included;
    // The macros the host's text defines (the define set and #define lines outside students'
    // files), which a student's file may neither redefine nor #undef.
    std::set<std::string> hostMacros;
    // Functions of the program no student's part may name -> whose they are (see expand).
    std::map<std::string, std::string> privateHelpers;
    // The macros the current student's part defined, #undef'd after it.
    std::set<std::string> studentMacros;
    // The current student's part's ShaderPart::unreachable.
    const std::map<std::string, std::string>* unreachable = nullptr;
    bool trace = false;  // the diagnosis build (kTraceNonFinite)
    // Whether the text being expanded is a traced part's own (not a file it includes).
    bool tracing = false;

    // What a student's part reads its built-ins through: definedBuiltins(), or in a traced
    // part of the diagnosis build a macro per traced built-in that passes the call's line.
    std::string builtinMacros(bool traced) const {
        std::string out;
        for (const std::string& builtin : builtinMacroNames()) out += "#undef " + builtin + "\n";
        for (const auto& [builtin, definition] : definedBuiltins())
            if (!traced) out += "#define " + builtin + " " + definition + "\n";
        if (traced)
            for (const TracedCall& c : tracedCalls())
                out += "#define " + c.builtin + (c.arguments == 2 ? "(x, y)" : "(x)") +
                       " pbrlab_trace_" + c.builtin + (c.arguments == 2 ? "(x, y" : "(x") +
                       ", __LINE__)\n";
        return out;
    }
    std::set<std::string> builtinMacroNames() const {
        std::set<std::string> names;
        for (const auto& [builtin, definition] : definedBuiltins()) names.insert(builtin);
        if (trace)
            for (const TracedCall& c : tracedCalls()) names.insert(c.builtin);
        return names;
    }

    int sourceIndex(const std::string& name) {
        out.sourceNames.push_back(name);
        return int(out.sourceNames.size() - 1);
    }

    // An include is looked up next to the including file, then in each root; whatever it
    // resolves to must stay inside a root (no "../" or symlink escapes).
    fs::path resolve(const std::string& target, const fs::path& from, const std::string& where) {
        std::vector<fs::path> candidates;
        if (!from.empty()) candidates.push_back(from.parent_path() / target);
        for (const auto& root : roots) candidates.push_back(root / target);
        for (const auto& c : candidates) {
            std::error_code ec;
            if (!fs::exists(c, ec)) {
                if (ec && ec != std::errc::no_such_file_or_directory)
                    throw Error(where + ": #include \"" + target + "\" cannot be read (" +
                                ec.message() + ")");
                continue;
            }
            bool allowed = false;
            for (const auto& root : roots) allowed = allowed || isInside(c, root);
            if (!allowed)
                throw Error(where + ": #include \"" + target +
                            "\" leaves the allowed shader folders");
            fs::path resolved = fs::canonical(c, ec);
            if (ec)
                throw Error(where + ": #include \"" + target + "\" cannot be resolved (" +
                            ec.message() + ")");
            return resolved;
        }
        throw Error(where + ": #include \"" + target + "\" not found");
    }

    std::string read(const fs::path& file) const {
        return studentFolder.empty() ? readText(file) : readStudentFile(file, studentFolder);
    }

    // Refuses what a student's file may not write (see ShaderPreprocessor::expand) and notes
    // the macros it defines.
    void screenStudentText(const std::string& text, const std::string& name) {
        auto refuse = [&](int line, const std::string& why) {
            throw ShaderError(name + ":" + std::to_string(line) + ": error: " + why);
        };
        int openComment = 0;
        const std::vector<CodeLine> lines = codeLines(text, &openComment);
        static const std::regex directive(R"(^\s*#\s*(\w+)\s*(\w*))");
        for (const CodeLine& l : lines) {
            std::smatch d;
            const size_t first = l.code.find_first_not_of(" \t\r");
            const bool isDirective = first != std::string::npos && l.code[first] == '#' &&
                                     std::regex_search(l.code, d, directive);
            if (isDirective && d[1].str() == "include") continue;  // its path is no name
            if (isDirective && (d[1].str() == "define" || d[1].str() == "undef")) {
                const std::string macro = d[2].str();
                if (hostMacros.count(macro))
                    refuse(l.lineAt(0), "#" + d[1].str() + " " + macro + ": " + macro +
                                            " is a macro of the host's (the program's code after "
                                            "your file reads it): a step's file may read it, "
                                            "but neither redefine nor #undef it");
                if (d[1].str() == "define" && macro.rfind("GL_", 0) != 0 &&
                    macro.find("__") == std::string::npos)
                    studentMacros.insert(macro);  // (the compiler refuses GL_ and __ names)
            }
            if (isDirective && l.code.find("##") != std::string::npos)
                refuse(l.lineAt(l.code.find("##")),
                       "token pasting (##) is not allowed in a step's file: it can form a name "
                       "the file does not write, such as a private helper of pbrlab's");
            forEachIdentifier(l.code, [&](const std::string& identifier, size_t at) {
                // The host's own macros say how it draws (PBRLAB_PROBE: points drawn alone,
                // as the grader draws them; PBRLAB_SKY: a picture with the sky behind): a
                // function that tested them could be right where it is graded and wrong in
                // the lab. The contract's macros (PI, NUM_LIGHTS) carry no such prefix.
                if (identifier.rfind("PBRLAB_", 0) == 0)
                    refuse(l.lineAt(at),
                           identifier +
                               " is one of the host's own macros (PBRLAB_...), which say how "
                               "the host draws your function, not what it computes: a step's "
                               "file may not name them. Your function must give the same "
                               "values wherever it is drawn.");
                auto helper = privateHelpers.find(identifier);
                if (helper != privateHelpers.end())
                    refuse(l.lineAt(at),
                           helper->first + " is private to " + helper->second +
                               ", which this program links: a step's file may not name it, nor "
                               "define a function of that name. Write that computation "
                               "yourself.");
            });
        }
        // A loop with no way out (grading/error_patterns.h reads it): what the compiler makes of it
        // depends on the rest of the program (measured on Mesa: ndotl's `while (true) { x += 1.0;
        // }` before its return gave 0 in a program with every step, the right value in one with
        // steps 1..4), so the function's value would not be its own. Refused at the loop.
        if (whyAlwaysZero(text).rfind("Your function has a loop that never ends", 0) == 0) {
            static const std::regex endless(
                R"(\bwhile\s*\(\s*(true|1)\s*\)|\bfor\s*\([^;()]*;\s*(true|1)?\s*;)");
            int at = 1;
            for (const CodeLine& l : lines) {
                std::smatch m;
                if (std::regex_search(l.code, m, endless)) {
                    at = l.lineAt(size_t(m.position(0)));
                    break;
                }
            }
            refuse(at,
                   "a loop that never ends (no break or return in it): a step's function "
                   "must return, and what the compiler makes of such a loop depends on the "
                   "rest of the program (it deletes the loop, or the code after it too), so "
                   "your function's value would not be its own. Give the loop a condition "
                   "that ends it.");
        }
        if (openComment)
            refuse(openComment,
                   "a /* comment that is not closed in this file: it would swallow the code "
                   "that follows your file in the program");
    }

    // After a student's part: a line that ends a continuation left on its last line, then an
    // #undef of every macro it defined, so none reaches the host's code after it.
    void closeStudentPart() {
        out.text += "\n";
        for (const std::string& macro : studentMacros) out.text += "#undef " + macro + "\n";
        studentMacros.clear();
        for (const std::string& builtin : builtinMacroNames())
            out.text += "#undef " + builtin + "\n";
    }

    // The file as the student names it: its path in the submission folder.
    std::string studentName(const fs::path& file) const {
        std::error_code ec;
        const fs::path folder = fs::weakly_canonical(studentFolder, ec);
        const fs::path relative = ec ? fs::path() : file.lexically_relative(folder);
        return relative.empty() || *relative.begin() == ".." ? file.filename().string()
                                                             : relative.generic_string();
    }

    void expandText(const std::string& original, const std::string& name, const fs::path& file) {
        int index = sourceIndex(name);
        std::string guarded;
        if (!studentFolder.empty()) {
            screenStudentText(original, name);
            out.studentTexts[index] = original;
            if (unreachable && !unreachable->empty()) out.unreachable[index] = *unreachable;
            guarded = guardLoops(original, name, studentName(file), out.loops);
        }
        const std::string& text = studentFolder.empty() ? original : guarded;
        out.text += "#line 1 " + std::to_string(index) + "\n";
        static const std::regex includeLine(R"(^\s*#\s*include\s*"([^"]+)\"\s*(//.*)?$)");
        static const std::regex versionLine(R"(^\s*#\s*version\b.*$)");
        static const std::regex hostDirective(R"(^\s*#\s*(extension|line)\b.*$)");
        std::istringstream in(text);
        std::string line;
        int lineNo = 0;
        while (std::getline(in, line)) {
            ++lineNo;
            if (!line.empty() && line.back() == '\r') line.pop_back();
            std::smatch m;
            if (std::regex_match(line, m, includeLine)) {
                std::string where = name + ":" + std::to_string(lineNo);
                fs::path target = resolve(m[1].str(), file, where);
                if (included.insert(target).second) {
                    out.files.push_back(target);
                    // A line the diagnosis build reports is one of the traced part's own.
                    const bool wasTracing = tracing;
                    if (wasTracing) out.text += builtinMacros(false);
                    tracing = false;
                    expandText(read(target), target.string(), target);
                    tracing = wasTracing;
                    if (wasTracing) out.text += builtinMacros(true);
                }
                out.text +=
                    "#line " + std::to_string(lineNo + 1) + " " + std::to_string(index) + "\n";
            } else if (std::regex_match(line, versionLine)) {
                out.text += "\n";  // the host writes #version once, first
            } else if (std::regex_match(line, m, hostDirective) && !studentFolder.empty()) {
                // The compiler accepts these only before any code, or would map its messages
                // through the student's #line: it reports them in the host's files.
                throw ShaderError(name + ":" + std::to_string(lineNo) + ": error: #" + m[1].str() +
                                  " is not allowed in a step's file: the host writes the "
                                  "program's #version, extensions and line markers (the step's "
                                  "file is pasted in the middle of the program)");
            } else {
                static const std::regex defineLine(R"(^\s*#\s*define\s+(\w+))");
                if (studentFolder.empty() && std::regex_search(line, m, defineLine))
                    hostMacros.insert(m[1].str());
                out.text += line + "\n";
            }
        }
    }
};

}  // namespace

ExpandedShader ShaderPreprocessor::expand(const std::vector<ShaderPart>& parts,
                                          const Defines& defines) const {
    Expander ex;
    ex.roots = roots_;
    ex.out.text = dialect_ == GlslDialect::Es300 ? kEs300Header : "#version 450 core\n";
    for (const auto& [name, value] : defines) {
        ex.out.text += "#define " + name + " " + value + "\n";
        ex.hostMacros.insert(name);
    }
    // The functions no student's part may name, found before any is read (one defined after
    // the student's part can still be called through a prototype): the private helpers of
    // every reference solution in the program, and the host's pbrlab_ functions after the
    // first student's part (common.glsl's, before it, are utilities that compute no step, and
    // the reference solutions call them).
    const bool anyStudent = std::any_of(
        parts.begin(), parts.end(), [](const ShaderPart& p) { return !p.studentFolder.empty(); });
    ex.trace = defines.count(kTraceNonFinite) != 0;
    if (anyStudent || ex.trace) ex.out.text += kDefinedBuiltins;
    if (ex.trace) ex.out.text += traceFunctions();
    if (anyStudent) {
        ex.out.text += loopGuardPrelude(ex.trace);
        ex.hostMacros.insert(kLoopGuardMacro);
        for (const std::string& name : loopGuardNames())
            ex.privateHelpers.emplace(name, "pbrlab's loop guard");
    }
    if (anyStudent)
        for (const std::string& builtin : ex.builtinMacroNames()) ex.hostMacros.insert(builtin);
    bool afterStudent = false;
    for (const auto& part : parts) {
        if (!anyStudent) break;  // no one to screen
        afterStudent = afterStudent || !part.studentFolder.empty();
        if (!part.studentFolder.empty() || (part.solutionOf.empty() && !afterStudent)) continue;
        const bool generated = !part.text.empty() || part.file.empty();
        for (const std::string& f : definedFunctions(generated ? part.text : readText(part.file))) {
            if (!part.solutionOf.empty() && f != part.solutionOf)
                ex.privateHelpers.emplace(f, "the reference solution of " + part.solutionOf);
            else if (part.solutionOf.empty() && f.rfind("pbrlab_", 0) == 0)
                ex.privateHelpers.emplace(f, "the host's code after your file");
        }
    }
    for (const auto& part : parts) {
        ex.unreachable = &part.unreachable;
        if (!part.text.empty() || part.file.empty()) {
            ex.roots = roots_;
            ex.studentFolder.clear();
            ex.expandText(part.text, part.name.empty() ? "<generated>" : part.name, {});
            continue;
        }
        std::error_code ec;
        fs::path file = fs::weakly_canonical(part.file, ec);
        if (ec) throw Error(part.file.string() + ": cannot be resolved (" + ec.message() + ")");
        if (!ex.included.insert(file).second) continue;
        ex.out.files.push_back(file);
        ex.studentFolder = part.studentFolder;
        ex.tracing = ex.trace && part.traced && !part.studentFolder.empty();
        if (!part.studentFolder.empty())  // the student's calls reach kDefinedBuiltins
            ex.out.text += ex.builtinMacros(ex.tracing);
        ex.roots = part.studentFolder.empty() ? roots_ : std::vector<fs::path>{part.studentFolder};
        // A student's file is read by the name it was given, so that the screening sees a
        // link as a link (and names the file as the student knows it).
        ex.expandText(ex.read(part.studentFolder.empty() ? file : part.file), file.string(), file);
        if (!part.studentFolder.empty()) ex.closeStudentPart();
        ex.tracing = false;
    }
    if (anyStudent && ex.trace) ex.out.text += loopGuardDiagnosis(ex.out.loops.size());
    return ex.out;
}

const std::vector<TracedCall>& tracedCalls() {
    static const std::vector<TracedCall> calls = {
        {"pow", 2, "pow with a negative base (or 0 to a power <= 0)",
         "pow with a result too large for a float (an overflow)"},
        {"sqrt", 1, "sqrt of a negative number", ""},
        {"inversesqrt", 1, "inversesqrt of a negative number or of 0", ""},
        {"log", 1, "log of a negative number or of 0", ""},
        {"log2", 1, "log2 of a negative number or of 0", ""},
        {"normalize", 1, "normalize of a zero vector (0/0)", ""},
        {"acos", 1, "acos of a number outside [-1, 1]", ""},
        {"asin", 1, "asin of a number outside [-1, 1]", ""},
        {"mod", 2, "mod(x, 0)", ""},
    };
    return calls;
}

const TracedCall* TraceSite::traced() const {
    const std::vector<TracedCall>& calls = tracedCalls();
    const int k = std::abs(call);
    return k >= 1 && k <= int(calls.size()) ? &calls[size_t(k - 1)] : nullptr;
}

const std::string& TraceSite::what() const {
    static const std::string none;
    const TracedCall* c = traced();
    return !c ? none : call < 0 && !c->overflow.empty() ? c->overflow : c->what;
}

TraceSite traceSite(double written) {
    // As pbrlab_noteCall writes it: (|call| x 65536 + line), negative for the overflow case.
    if (!std::isfinite(written) || std::abs(written) >= 2147483647.0) return {};
    const long site = std::lround(written);
    const long magnitude = std::labs(site);
    return {int(magnitude / 65536) * (site < 0 ? -1 : 1), int(magnitude % 65536)};
}

const std::map<std::string, std::string>& definedBuiltins() {
    static const std::map<std::string, std::string> routed = {{"pow", "pbrlab_definedPow"}};
    return routed;
}

std::string mapCompilerLog(const std::string& log, const std::vector<std::string>& sourceNames) {
    // ANGLE (Chromium's WebGL 2) writes "ERROR: 0:12: ...": rewritten first, its source
    // number only when it names a source (an unknown one stays a number, which the pattern
    // below, with its parentheses, never matches).
    static const std::regex angle(R"((^|\n)(ERROR|WARNING): (\d+):(\d+):)");
    std::string angleMapped;
    {
        auto begin = log.cbegin();
        std::smatch m;
        while (std::regex_search(begin, log.cend(), m, angle)) {
            angleMapped.append(begin, m[0].first);
            const size_t index = std::stoul(m[3].str());
            const std::string name = index < sourceNames.size() ? sourceNames[index] : m[3].str();
            angleMapped += m[1].str() + m[2].str() + ": " + name + ":" + m[4].str() + ":";
            begin = m[0].second;
        }
        angleMapped.append(begin, log.cend());
    }
    // Mesa writes "0:12(5): error: ...", others "0(12) : error ...".
    static const std::regex ref(R"((^|\n|\s)(\d+)(:(\d+)\((\d+)\)|\((\d+)\)))");
    const std::string& source = angleMapped;
    std::string result;
    auto begin = source.cbegin();
    std::smatch m;
    while (std::regex_search(begin, source.cend(), m, ref)) {
        result.append(begin, m[0].first);
        size_t index = std::stoul(m[2].str());
        std::string name = index < sourceNames.size() ? sourceNames[index] : m[2].str();
        result += m[1].str() + name + ":" +
                  (m[4].matched ? m[4].str() + "(" + m[5].str() + ")" : m[6].str());
        begin = m[0].second;
    }
    result.append(begin, source.cend());
    return result;
}

namespace {

// The line (1-based) of the first line of `text` that `matches`, or 0.
template <class Matches>
int firstLine(const std::string& text, Matches matches) {
    std::istringstream in(text);
    int lineNo = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNo;
        if (matches(line)) return lineNo;
    }
    return 0;
}

// The line of a definition or prototype of function `name` in `text`, or 0.
int definitionLine(const std::string& text, const std::string& name) {
    const std::regex definition("^\\s*(\\w+\\s+)+" + name + "\\s*\\(");
    return firstLine(text, [&](const std::string& line) {
        std::smatch m;
        return std::regex_search(line, m, definition) && m[1].str().rfind("return", 0) != 0;
    });
}

// The line of the first call of function `name` in `text` (comments left out), or 0.
int callLine(const std::string& text, const std::string& name) {
    const std::regex call("\\b" + name + "\\s*\\(");
    return firstLine(text, [&](const std::string& line) {
        return std::regex_search(line.substr(0, line.find("//")), call);
    });
}

// Whether line `line` (from 1) of `text` calls `name`.
bool lineHas(const std::string& text, int line, const std::string& name) {
    std::istringstream in(text);
    std::string l;
    int at = 0;
    while (at < line && std::getline(in, l)) ++at;
    const std::regex call("\\b" + name + "\\s*\\(");
    return line > 0 && at == line && std::regex_search(l.substr(0, l.find("//")), call);
}

// The body of the first definition of `name` (its braces), or "".
std::string bodyOf(const std::string& text, const std::string& name) {
    const std::regex definition("\\b" + name + "\\s*\\([^)]*\\)\\s*\\{");
    std::smatch m;
    if (!std::regex_search(text, m, definition)) return "";
    const size_t open = size_t(m.position(0) + m.length(0) - 1);
    int depth = 0;
    for (size_t i = open; i < text.size(); ++i) {
        depth += text[i] == '{' ? 1 : text[i] == '}' ? -1 : 0;
        if (depth == 0) return text.substr(open, i - open + 1);
    }
    return text.substr(open);
}

// What ShaderPart::unreachable says about `name` for the student's source `index`, or "".
std::string unreachableReason(const ExpandedShader& shader, int index, const std::string& name) {
    auto names = shader.unreachable.find(index);
    if (names == shader.unreachable.end()) return "";
    auto why = names->second.find(name);
    return why == names->second.end() ? "" : why->second;
}

bool isStudentSource(const ExpandedShader& shader, const std::string& file) {
    for (const auto& [index, text] : shader.studentTexts)
        if (size_t(index) < shader.sourceNames.size() && shader.sourceNames[size_t(index)] == file)
            return true;
    return false;
}

// What to say about a function of the student's file that the compiler names in `message`.
std::string hintFor(const std::string& message, const std::string& name, const std::string& code,
                    const std::vector<std::string>& hostNames) {
    const bool hosts = std::find(hostNames.begin(), hostNames.end(), name) != hostNames.end();
    if (message.find("redefined") != std::string::npos) {
        if (name == "main")
            return "main is the host's (it calls your function for every pixel): a step's file "
                   "holds only your function and helpers of your own.";
        // A contract function's redefinition is hinted by the grader, which knows its step.
        return hosts ? "" : name + " is already defined by pbrlab: give your helper another name.";
    }
    if (message.find("recursion") != std::string::npos) {
        const std::string body = bodyOf(code, name);
        const std::regex call("\\b" + name + "\\s*\\(");
        if (!body.empty() && std::regex_search(body, call))
            return name + " calls itself, and GLSL allows no recursion: write it as a loop.";
        return name + " is part of a cycle of calls" +
               (hosts ? " through a contract function that calls yours back" : "") +
               ", and GLSL allows no recursion: compute that part yourself.";
    }
    return "";
}

// "file:L(C): error: message" as mapCompilerLog writes Mesa's messages.
const std::regex& locatedMessage() {
    static const std::regex located(R"(^(.*):(\d+)\((\d+)\): (error|warning): (.*)$)");
    return located;
}

// The log with each routed built-in's definition (definedBuiltins()) named as the built-in.
std::string withBuiltinNames(std::string mapped) {
    for (const auto& [builtin, definition] : definedBuiltins())
        for (size_t at = mapped.find(definition); at != std::string::npos;
             at = mapped.find(definition, at + builtin.size()))
            mapped.replace(at, definition.size(), builtin);
    return mapped;
}

// The host's function names a student may collide with: contract functions are declared
// by prototypes (each before its step's part); others are found by their definition in
// the host's text.
std::vector<std::string> hostFunctionNames(const ExpandedShader& shader) {
    std::vector<std::string> hostNames;
    static const std::regex prototype(R"(^\s*\w+\s+(\w+)\s*\([^;{]*\)\s*;)");
    static const std::regex marker(R"(^#line \d+ (\d+)$)");
    std::istringstream in(shader.text);
    int source = -1;
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (std::regex_match(line, m, marker))
            source = std::stoi(m[1].str());
        else if (!shader.studentTexts.count(source) && std::regex_search(line, m, prototype))
            hostNames.push_back(m[1].str());
    }
    return hostNames;
}

// "student file:line" of the student's call of the routed built-in `message` names (at the
// reported `line` if that line calls it, else its first call), or "".
std::string routedBuiltinAt(const ExpandedShader& shader, const std::string& message, int line) {
    for (const auto& [builtin, definition] : definedBuiltins()) {
        const std::regex named("\\b" + builtin + "\\b");
        if (!std::regex_search(message, named)) continue;
        for (const auto& [index, code] : shader.studentTexts) {
            const int at = lineHas(code, line, builtin) ? line : callLine(code, builtin);
            if (at) return shader.sourceNames[size_t(index)] + ":" + std::to_string(at);
        }
    }
    return "";
}

// The loop guard's wrapping (loop_guard.h) of a condition that is not a bool: the
// compiler names pbrlab_loop, which the student never wrote. (Mesa reports it, and its
// own "loop condition must be scalar boolean" after it, at a line of common.glsl.) The
// message said in the student's terms, at the place the compiler gave.
std::string loopConditionMessage(const std::string& line) {
    static const std::regex angleLocated(R"(^((ERROR|WARNING): [^:]+:\d+:))");
    const std::string what =
        " a loop's condition must be a bool (GLSL converts no number to one: `i != 0`, "
        "not `i`)";
    std::smatch m;
    return std::regex_match(line, m, locatedMessage())
               ? m[1].str() + ":" + m[2].str() + "(" + m[3].str() + "): error:" + what
           : std::regex_search(line, m, angleLocated) ? m[1].str() + what
                                                      : "error:" + what;
}

// Whether `out` ends with `line` and its newline (a message's candidates repeat it).
bool endsWithLine(const std::string& out, const std::string& line) {
    return out.size() >= line.size() + 1 &&
           out.compare(out.size() - line.size() - 1, line.size() + 1, line + "\n") == 0;
}

// A located message (`m`) about a call of `name`, which the program does not declare, moved
// to the student's call; `line` as it is when no student's file calls it.
std::string undeclaredCallLine(const ExpandedShader& shader, const std::smatch& m,
                               const std::string& name, const std::string& line) {
    for (const auto& [index, code] : shader.studentTexts) {
        const int at = callLine(code, name);
        if (at == 0) continue;
        const std::string why = unreachableReason(shader, index, name);
        return shader.sourceNames[size_t(index)] + ":" + std::to_string(at) + ": " + m[4].str() +
               ": " + (why.empty() ? m[5].str() : why);
    }
    return line;
}

// A located message (`m`) of the host's code about function `name`, moved to the student's
// file with a hint; `line` as it is when no student's file defines (or, for recursion, calls)
// it.
std::string namedFunctionLine(const ExpandedShader& shader, const std::smatch& m,
                              const std::string& name, const std::vector<std::string>& hostNames,
                              const std::string& line) {
    const std::string message = m[5].str();
    for (const auto& [index, code] : shader.studentTexts) {
        // Where the student defines the function, else where the student calls it
        // (a host function in the cycle is reached from the student's call).
        const int defined = definitionLine(code, name);
        const bool recursion = message.find("recursion") != std::string::npos;
        const int at = defined ? defined : recursion ? callLine(code, name) : 0;
        if (at == 0) continue;
        const std::string hint = defined ? hintFor(message, name, code, hostNames)
                                         : "you call " + name +
                                               ", which calls your function back, and GLSL "
                                               "allows no recursion: compute that part yourself.";
        return shader.sourceNames[size_t(index)] + ":" + std::to_string(at) + ": " + m[4].str() +
               ": " + message + (hint.empty() ? "" : "\nhint: " + hint);
    }
    return line;
}

}  // namespace

std::string mapCompilerLog(const std::string& log, const ExpandedShader& shader) {
    // A student wrote the built-in's name: messages about its definition say that name.
    const std::string mapped = withBuiltinNames(mapCompilerLog(log, shader.sourceNames));
    if (shader.studentTexts.empty()) return mapped;
    const std::regex& located = locatedMessage();
    // The function a message is about: `name' redefined, `float name(float)' has static
    // recursion.
    static const std::regex named(R"(`(?:[\w ]*\s)?(\w+)(?:\([^']*\))?')");
    const std::vector<std::string> hostNames = hostFunctionNames(shader);
    // A call of a function the program does not declare. Mesa reports it at a wrong source
    // string (common.glsl's), so it is moved to the student's call; a contract function of a
    // later step is said as such (ShaderPart::unreachable).
    static const std::regex undeclared(R"(no function with name '(\w+)')");
    // Mesa reports a message about a macro's expansion in source string 0 at the student's
    // line: one naming a routed built-in (definedBuiltins()) is moved to the student's
    // file, and so is every message after it at the same place (its candidates, what follows
    // from it).
    std::map<std::string, std::string> movedPlaces;  // "file:line" -> "student file:line"
    std::istringstream in(mapped);
    std::string out;
    for (std::string line; std::getline(in, line);) {
        std::smatch m, n;
        if (line.find("pbrlab_loop") != std::string::npos) {
            line = loopConditionMessage(line);
            if (endsWithLine(out, line)) continue;  // its candidates, said once
            out += line + "\n";
            continue;
        }
        if (std::regex_match(line, m, located) && !isStudentSource(shader, m[1].str())) {
            const std::string place = m[1].str() + ":" + m[2].str();
            if (!movedPlaces.count(place)) {
                const std::string to = routedBuiltinAt(shader, m[5].str(), std::stoi(m[2].str()));
                if (!to.empty()) movedPlaces[place] = to;
            }
            if (movedPlaces.count(place)) {
                out += movedPlaces[place] + ": " + m[4].str() + ": " + m[5].str() + "\n";
                continue;
            }
        }
        if (std::regex_match(line, m, located) && std::regex_search(line, n, undeclared))
            line = undeclaredCallLine(shader, m, n[1].str(), line);
        else if (std::regex_match(line, m, located) && !isStudentSource(shader, m[1].str()) &&
                 std::regex_search(line, n, named))
            line = namedFunctionLine(shader, m, n[1].str(), hostNames, line);
        out += line + "\n";
    }
    if (!mapped.empty() && mapped.back() != '\n' && !out.empty()) out.pop_back();
    return out;
}

}  // namespace pbrlab
