// GLSL assembly: #include "..." resolved only inside allowed roots, #define injection, and
// #line markers so compiler messages can be mapped back to the original file and line.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "shader/loop_guard.h"
#include "util/error.h"

namespace pbrlab {

// A compile or link failure; what() is the compiler log with file:line references (or a
// directive the preprocessor refused in a student's file, with its file:line).
struct ShaderError : Error {
    using Error::Error;
};

// Name -> value; the map keeps them sorted, which makes the set a stable cache key.
using Defines = std::map<std::string, std::string>;

// One piece of a shader: a file, or text made by the host (named for error messages).
struct ShaderPart {
    ShaderPart(std::filesystem::path f) : file(std::move(f)) {}
    ShaderPart(std::string partName, std::string partText)
        : text(std::move(partText)), name(std::move(partName)) {}
    std::filesystem::path file;  // used when text is empty
    std::string text;
    std::string name;  // for generated text: what to call it in messages
    // When set, this part is a student's file of this submission folder: it and every file it
    // #includes are screened and read by readStudentFile (student_file.h), and its includes
    // resolve inside this folder only, never in the reference solutions.
    std::filesystem::path studentFolder;
    // A student's part: the names it cannot call, each with what to tell a student who does
    // (said in place of the compiler's "no function with name"): the contract functions of
    // later steps (contract.h, unreachableFrom).
    std::map<std::string, std::string> unreachable;
    // A student's part whose calls the diagnosis build traces (kTraceNonFinite): the graded
    // step's file, so that a line reported is one of that file.
    bool traced = false;
    // A reference solution linked as host code (not the student's part): the contract function
    // it defines. Every other function it defines is a private helper of that solution, and no
    // student's part of the program may name it (see ShaderPreprocessor::expand).
    std::string solutionOf;
};

struct ExpandedShader {
    std::string text;
    // GLSL source-string number -> the file it came from (what #line markers refer to).
    std::vector<std::string> sourceNames;
    // Every file read, for hot reload.
    std::vector<std::filesystem::path> files;
    // Source-string number -> the text of a student's file (the part with a studentFolder,
    // and what it includes): compiler messages that point elsewhere are traced back to it.
    std::map<int, std::string> studentTexts;
    // Source-string number of a student's file -> ShaderPart::unreachable of its part.
    std::map<int, std::map<std::string, std::string>> unreachable;
    // The loops of the students' files, as the guard numbers them (loop_guard.h): loop K is
    // loops[K - 1].
    std::vector<LoopSite> loops;
};

// The GLSL the host writes every program in. Es300 is WebGL 2's (OpenGL ES 3.00), for the
// lab in a browser: its own #version line, default precisions (an ES fragment shader has
// none for float, and samplers default to lowp), and the two GLSL 4.00 built-ins the steps
// use that ES 3.00 lacks, as user functions of the same names (bitfieldReverse: hammersley's
// solution; findMSB: irradiance's), which ES 3.00 does not reserve. Everything else the
// programs use is common to both (tests/test_glsl_es.cpp renders every step in both).
enum class GlslDialect { Desktop450, Es300 };

class ShaderPreprocessor {
public:
    explicit ShaderPreprocessor(std::vector<std::filesystem::path> roots,
                                GlslDialect dialect = GlslDialect::Desktop450);

    // The dialect's header ("#version 450 core"), the defines, then each part with its includes
    // expanded (each file at most once). Throws pbrlab::Error naming file and line for a missing
    // include or one that leaves the roots.
    //
    // A student's part (and what it includes) is screened so that nothing it writes reaches
    // code that is not its own; each refusal is a ShaderError at the student's line:
    // - a name of a private helper of a reference solution in the program, or of one of the
    //   host's pbrlab_ functions after the student's part (a call, a prototype, a definition or
    //   a macro of that name), and token pasting (##), which could form such a name: those
    //   helpers compute parts of other steps. The student's own helpers may have any other
    //   name, pbrlab_ included (the kit's stub of a step keeps its reference's helper), and
    //   common.glsl's pbrlab_ utilities, declared before every step, compute no step;
    // - #define or #undef of a macro the host defines (the define set, NUM_LIGHTS, ...): the
    //   host's code after the part reads it;
    // - a /* comment still open at the end of a file: it would swallow the host's code after it;
    // - a loop the guard cannot bound (guardLoops).
    // Every loop of such a part is bounded by the guard (loop_guard.h), whose budget uniform the
    // program then declares.
    // Every macro the part defines is #undef'd after it, so the host's code after the part
    // reads none of them. (Undefining rather than refusing every macro: a student's own macros
    // are legitimate GLSL and harm nothing once they end with the file; refusing is kept for
    // the host's names, whose #undef would change the host's code.)
    ExpandedShader expand(const std::vector<ShaderPart>& parts, const Defines& defines) const;

    const std::vector<std::filesystem::path>& roots() const { return roots_; }

private:
    std::vector<std::filesystem::path> roots_;
    GlslDialect dialect_;
};

// Rewrites "S:L(C)" / "S(L)" source references in a compiler log to "file:L(C)".
std::string mapCompilerLog(const std::string& log, const std::vector<std::string>& sourceNames);

// The built-ins a student's part reaches through a macro of their name, so that the cases GLSL
// leaves undefined (pow of a negative base) compute the same on every GPU: built-in -> the
// host's function the program defines before the first student's part.
const std::map<std::string, std::string>& definedBuiltins();

// The diagnosis build, when the define set holds kTraceNonFinite: each call the traced part
// (ShaderPart::traced, not the files it includes) makes of a built-in that can turn finite
// arguments into a NaN or an Inf (pow of a negative base, sqrt of a negative, normalize of a
// zero vector ...) is checked, and a non-finite result of finite arguments is noted and
// replaced by 0. The view writes out, in place of its value (shaders/view_main.frag): the
// first call that made one (its site, traceSite), another call that made one at that point
// (its site, 0: none), and whether the value with those results replaced is finite (1, else
// 0): whether the NaN or Inf the student sees came from those calls. Feedback renders the
// points where a value is not finite with it.
inline constexpr const char* kTraceNonFinite = "PBRLAB_TRACE_NONFINITE";
struct TracedCall {
    std::string builtin;  // "pow"
    int arguments;        // 1 or 2
    std::string what;     // what made the NaN or Inf, for the student
    // pow only: what it is when the arguments lie where the built-in is defined (a result too
    // large for a float); "": `what` is every case.
    std::string overflow;
};
const std::vector<TracedCall>& tracedCalls();
// A site as the diagnosis build writes it: the traced call (its index in tracedCalls() + 1,
// negative for its `overflow` case) and the line of the student's file.
struct TraceSite {
    int call = 0, line = 0;
    const TracedCall* traced() const;  // null: no site
    const std::string& what() const;   // what made it, for the student
};
TraceSite traceSite(double written);

// mapCompilerLog, then every message that a student's file caused but the compiler reports
// elsewhere (Mesa loses the source number of a redefinition and reports a recursion at 0:0)
// is moved to the student's line that caused it, with a hint where one is true: a function
// the host defines (main, a contract function), a function that calls itself, a cycle of
// calls through a contract function.
std::string mapCompilerLog(const std::string& log, const ExpandedShader& shader);

}  // namespace pbrlab
