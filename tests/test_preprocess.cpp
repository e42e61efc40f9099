#include <gtest/gtest.h>

#include "shader/preprocess.h"
#include "test_support.h"
#include "util/error.h"

using namespace pbrlab;
using pbrlab::test::TempDir;

namespace {

// Finds the (source, line) that the expanded text attributes to `needle`'s line, by
// replaying the #line markers as a GLSL compiler would.
std::pair<std::string, int> originOf(const ExpandedShader& s, const std::string& needle) {
    std::istringstream in(s.text);
    std::string line;
    int source = 0, lineNo = 0;
    while (std::getline(in, line)) {
        if (line.rfind("#line ", 0) == 0) {
            std::istringstream l(line.substr(6));
            l >> lineNo >> source;
            continue;  // the next line has number lineNo
        }
        if (line.find(needle) != std::string::npos)
            return {s.sourceNames.at(size_t(source)), lineNo};
        ++lineNo;
    }
    return {"", -1};
}

}  // namespace

TEST(Preprocessor, ExpandsIncludesAndKeepsOriginalLineNumbers) {
    TempDir dir;
    dir.write("lib/b.glsl", "// b\nfloat b() { return 1.0; }\n");
    auto a = dir.write("a.glsl", "// a\n#include \"lib/b.glsl\"\nfloat a() { return b(); }\n");
    ShaderPreprocessor pre({dir.path});
    ExpandedShader s = pre.expand({a}, {{"NUM_LIGHTS", "4"}});
    EXPECT_EQ(s.text.rfind("#version 450 core\n", 0), 0u);
    EXPECT_NE(s.text.find("#define NUM_LIGHTS 4"), std::string::npos);
    auto [bFile, bLine] = originOf(s, "float b()");
    EXPECT_NE(bFile.find("b.glsl"), std::string::npos);
    EXPECT_EQ(bLine, 2);
    auto [aFile, aLine] = originOf(s, "float a()");
    EXPECT_NE(aFile.find("a.glsl"), std::string::npos);
    EXPECT_EQ(aLine, 3);
    EXPECT_EQ(s.files.size(), 2u);
}

TEST(Preprocessor, IncludesEachFileOnce) {
    TempDir dir;
    dir.write("c.glsl", "float c() { return 2.0; }\n");
    auto a = dir.write("a.glsl", "#include \"c.glsl\"\n#include \"c.glsl\"\n");
    ExpandedShader s = ShaderPreprocessor({dir.path}).expand({a}, {});
    const size_t first = s.text.find("float c()");
    ASSERT_NE(first, std::string::npos) << "c.glsl not included at all:\n" << s.text;
    EXPECT_EQ(s.text.find("float c()", first + 1), std::string::npos) << "included twice";
}

TEST(Preprocessor, RefusesIncludesThatLeaveTheRoots) {
    TempDir dir;
    dir.write("secret.glsl", "float secret;\n");
    auto a = dir.write("root/a.glsl", "\n#include \"../secret.glsl\"\n");
    try {
        ShaderPreprocessor({dir.path / "root"}).expand({a}, {});
        FAIL() << "escape not refused";
    } catch (const Error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("a.glsl:2"), std::string::npos) << m;
        EXPECT_NE(m.find("leaves the allowed"), std::string::npos) << m;
    }
}

TEST(Preprocessor, RefusesSymlinksPointingOutside) {
    TempDir dir;
    dir.write("outside.glsl", "float x;\n");
    std::filesystem::create_directories(dir.path / "root");
    std::filesystem::create_symlink(dir.path / "outside.glsl", dir.path / "root/link.glsl");
    auto a = dir.write("root/a.glsl", "#include \"link.glsl\"\n");
    EXPECT_THROW(ShaderPreprocessor({dir.path / "root"}).expand({a}, {}), Error);
}

TEST(Preprocessor, MissingIncludeNamesFileAndLine) {
    TempDir dir;
    auto a = dir.write("a.glsl", "\n\n#include \"nope.glsl\"\n");
    try {
        ShaderPreprocessor({dir.path}).expand({a}, {});
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("a.glsl:3"), std::string::npos) << e.what();
    }
}

TEST(Preprocessor, DropsVersionLinesOfIncludedFilesWithoutShiftingLines) {
    TempDir dir;
    auto a = dir.write("a.glsl", "#version 330 core\nfloat a;\n");
    ExpandedShader s = ShaderPreprocessor({dir.path}).expand({a}, {});
    EXPECT_EQ(s.text.find("#version 330"), std::string::npos);
    EXPECT_EQ(originOf(s, "float a;").second, 2);
}

TEST(CompilerLog, MapsSourceNumbersToFiles) {
    std::vector<std::string> names = {"<generated>", "/kit/ndotl.glsl"};
    EXPECT_EQ(mapCompilerLog("1:7(12): error: syntax error", names),
              "/kit/ndotl.glsl:7(12): error: syntax error");
    EXPECT_EQ(mapCompilerLog("ERROR: 1(7) : bad", names), "ERROR: /kit/ndotl.glsl:7 : bad");
    // ANGLE's (Chromium's WebGL 2): "ERROR: S:L: ...", each message on its line.
    EXPECT_EQ(mapCompilerLog("ERROR: 1:11: 'x' : undeclared identifier\n"
                             "WARNING: 0:3: 'y' : unused\nERROR: 9:2: out of range",
                             names),
              "ERROR: /kit/ndotl.glsl:11: 'x' : undeclared identifier\n"
              "WARNING: <generated>:3: 'y' : unused\nERROR: 9:2: out of range");
}

// What a student's part may write (ShaderPreprocessor::expand): nothing it writes reaches code
// that is not its own.
namespace {

// A program as viewRecipe lays it out: a reference solution linked as host code (with a private
// helper), the student's file, the host's code after it (an empty generated part among it: a
// step without parameters declares none).
struct StudentProgram {
    TempDir dir;
    std::filesystem::path kit = dir.path / "kit";
    ShaderPart solution{
        dir.write("host/earlier.glsl",
                  "float pbrlab_earlierHelper(float x)\n{\n    return x;\n}\n"
                  "float earlier(float x)\n{\n    return pbrlab_earlierHelper(x);\n}\n")};
    std::filesystem::path after = dir.write("host/after.glsl",
                                            "float pbrlab_hostAfter() { return 1.0; }\n"
                                            "float after() { return pbrlab_hostAfter(); }\n");

    ExpandedShader expand(const std::string& studentText) {
        dir.write("kit/step.glsl", studentText);
        solution.solutionOf = "earlier";
        ShaderPart student(kit / "step.glsl");
        student.studentFolder = kit;
        return ShaderPreprocessor({dir.path / "host"})
            .expand({solution, student, ShaderPart("<parameters>", ""), after},
                    {{"NUM_LIGHTS", "2"}});
    }
    // The refusal's text, or "" when the file is accepted.
    std::string refusal(const std::string& studentText) {
        try {
            expand(studentText);
        } catch (const ShaderError& e) {
            return e.what();
        }
        return "";
    }
};

}  // namespace

TEST(Preprocessor, AStudentsFileCannotNameAPrivateHelperOfAReferenceSolution) {
    StudentProgram p;
    // Every way of naming it: a call, a prototype, a definition of that name, a macro, and a
    // name hidden from a reader who does not join continuation lines the way the compiler does.
    for (const std::string code : {
             "float step(float x) { return pbrlab_earlierHelper(x); }\n",
             "float pbrlab_earlierHelper(float x);\nfloat step(float x) { return x; }\n",
             "float pbrlab_earlierHelper(float x) { return 2.0 * x; }\n",
             "#define H pbrlab_earlierHelper\nfloat step(float x) { return H(x); }\n",
             "/* a comment *\\\n/ float step(float x) { return pbrlab_earlierHelper(x); }\n",
         }) {
        SCOPED_TRACE(code);
        const std::string why = p.refusal(code);
        EXPECT_NE(why.find("pbrlab_earlierHelper is private to the reference solution of "
                           "earlier"),
                  std::string::npos)
            << why;
        EXPECT_NE(why.find("step.glsl:"), std::string::npos) << why;
    }
    // The host's pbrlab_ functions after the student's part, callable through a prototype.
    EXPECT_NE(p.refusal("float pbrlab_hostAfter();\nfloat step(float x) { return x; }\n")
                  .find("pbrlab_hostAfter is private to the host's code after your file"),
              std::string::npos);
    // Token pasting could form the name without writing it.
    EXPECT_NE(p.refusal("#define CAT(a, b) a##b\nfloat step(float x) { return "
                        "CAT(pbrlab_earlier, Helper)(x); }\n")
                  .find("step.glsl:1: error: token pasting (##) is not allowed"),
              std::string::npos);
    // The same name in a comment, the contract function itself, and helpers of the student's
    // own (pbrlab_ included: the kit's stubs keep their step's own helper) are fine.
    EXPECT_EQ(p.refusal("// pbrlab_earlierHelper would do it\n/* pbrlab_earlierHelper */\n"
                        "float pbrlab_mine(float x) { return earlier(x); }\n"
                        "float step(float x) { return pbrlab_mine(x); }\n"),
              "");
}

TEST(Preprocessor, AStudentsMacrosEndWithItsFile) {
    StudentProgram p;
    const ExpandedShader s = p.expand(
        "#define SCALE 2.0\n#define twice(x) (SCALE * (x))\n"
        "float step(float x) { return twice(x); } // \\\n");
    // After the student's text: a line that ends its continuation, then every macro undone,
    // before the host's code.
    const size_t after = s.text.find("float after()");
    const size_t undoScale = s.text.find("#undef SCALE\n"),
                 undoTwice = s.text.find("#undef twice\n");
    ASSERT_NE(undoScale, std::string::npos) << s.text;
    ASSERT_NE(undoTwice, std::string::npos) << s.text;
    EXPECT_LT(undoScale, after);
    EXPECT_LT(undoTwice, after);
    EXPECT_GT(undoScale, s.text.find("float step("));
    EXPECT_NE(s.text.find("// \\\n\n"), std::string::npos)
        << "the continuation ends on a blank line";
}

TEST(Preprocessor, AStudentsFileCannotRedefineOrUndefineTheHostsMacros) {
    StudentProgram p;
    for (const std::string directive : {"#undef NUM_LIGHTS", "#define NUM_LIGHTS"}) {
        const std::string why = p.refusal(directive + " \nfloat step(float x) { return x; }\n");
        EXPECT_NE(
            why.find("step.glsl:1: error: " + directive + ": NUM_LIGHTS is a macro of the host's"),
            std::string::npos)
            << why;
    }
    // Reading it is what the contract allows.
    EXPECT_EQ(p.refusal("float step(float x) { return x * float(NUM_LIGHTS); }\n"), "");
}

// The diagnosis build (kTraceNonFinite) traces the graded step's own file: a line it reports is
// one of that file, not of a file it includes nor of an earlier step's.
TEST(Preprocessor, TheDiagnosisBuildTracesTheGradedFilesOwnCallsOnly) {
    TempDir dir;
    dir.write("student/lib.glsl", "float helper(float x) { return sqrt(x); }\n");
    ShaderPart graded(dir.write("student/step.glsl",
                                "#include \"lib.glsl\"\nfloat own(float x) { return sqrt(x); }\n"
                                "float after(float x) { return sqrt(helper(x)); }\n"));
    graded.studentFolder = dir.path / "student";
    graded.traced = true;
    ShaderPart earlier(dir.write("earlier/earlier.glsl", "float g(float x) { return sqrt(x); }\n"));
    earlier.studentFolder = dir.path / "earlier";
    const ShaderPreprocessor pre({dir.path});
    const ExpandedShader s = pre.expand({earlier, graded}, {{kTraceNonFinite, "1"}});
    // The definition of sqrt in force at a line of the expanded text ("": none).
    auto sqrtAt = [&](const std::string& needle) {
        const size_t at = s.text.find(needle);
        EXPECT_NE(at, std::string::npos) << needle;
        const size_t define = s.text.rfind("#define sqrt", at),
                     undo = s.text.rfind("#undef sqrt", at);
        if (define == std::string::npos || (undo != std::string::npos && undo > define))
            return std::string();
        return s.text.substr(define, s.text.find('\n', define) - define);
    };
    const std::string traced = "#define sqrt(x) pbrlab_trace_sqrt(x, __LINE__)";
    EXPECT_EQ(sqrtAt("float own("), traced);
    EXPECT_EQ(sqrtAt("float after("), traced);
    EXPECT_EQ(sqrtAt("float helper("), "");
    EXPECT_EQ(sqrtAt("float g("), "");
    // The build without it traces nothing.
    EXPECT_EQ(pre.expand({earlier, graded}, {}).text.find("pbrlab_trace_"), std::string::npos);
}

// The host's own macros say how it draws (points alone, a sky behind): a function that read
// them could be right where it is graded and wrong in the lab's pictures.
TEST(Preprocessor, AStudentsFileCannotNameTheHostsOwnMacros) {
    StudentProgram p;
    for (const std::string line :
         {"#ifdef PBRLAB_PROBE", "#if defined(PBRLAB_SKY)", "#ifndef PBRLAB_ANY_FUTURE_NAME"}) {
        const std::string why =
            p.refusal(line +
                      "\nfloat step(float x) { return x; }\n#else\nfloat step(float x) "
                      "{ return 2.0 * x; }\n#endif\n");
        EXPECT_NE(why.find("step.glsl:1: error: PBRLAB_"), std::string::npos)
            << line << ": " << why;
        EXPECT_NE(why.find("is one of the host's own macros"), std::string::npos) << why;
    }
    EXPECT_NE(p.refusal("float step(float x) { return x; }\n\n#define PBRLAB_MINE 1\n")
                  .find("step.glsl:3: error: PBRLAB_MINE"),
              std::string::npos);
    // In a comment it is no name.
    EXPECT_EQ(p.refusal("// not PBRLAB_PROBE\nfloat step(float x) { return x; }\n"), "");
}

TEST(Preprocessor, AStudentsFileCannotLeaveACommentOpen) {
    StudentProgram p;
    const std::string why = p.refusal("float step(float x) { return x; }\n\n/* the rest\n");
    EXPECT_NE(why.find("step.glsl:3: error: a /* comment that is not closed"), std::string::npos)
        << why;
}

// A call of a function the program does not declare: Mesa reports it in another source string;
// the log names the student's call, and for a later step's contract function, why.
TEST(CompilerLog, ACallOfALaterStepsFunctionIsNamedAtTheStudentsLine) {
    StudentProgram p;
    p.dir.write("kit/step.glsl", "float step(float x)\n{\n    return later(x);\n}\n");
    ShaderPart student(p.kit / "step.glsl");
    student.studentFolder = p.kit;
    student.unreachable = {{"later", "later is introduced in step 9 (later); step cannot call it"}};
    const ExpandedShader s = ShaderPreprocessor({p.dir.path / "host"}).expand({student}, {});
    const std::string log = "0:3(9): error: no function with name 'later'\n";
    EXPECT_EQ(mapCompilerLog(log, s),
              (p.kit / "step.glsl").string() +
                  ":3: error: later is introduced in step 9 (later); step cannot call it\n");
    // A name that is no contract function keeps the compiler's words, at the student's call.
    p.dir.write("kit/step.glsl", "float step(float x)\n{\n    return typo(x);\n}\n");
    const ExpandedShader t = ShaderPreprocessor({p.dir.path / "host"}).expand({student}, {});
    EXPECT_EQ(mapCompilerLog("0:3(9): error: no function with name 'typo'\n", t),
              (p.kit / "step.glsl").string() + ":3: error: no function with name 'typo'\n");
}
