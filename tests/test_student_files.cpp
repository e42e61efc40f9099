// One screening path for a student's files (shader/student_file.h): every hostile kind of
// file is refused with the same words by every command that reads a student's file, and none
// of them blocks. Each command runs under `timeout`, so a hang fails the test instead of
// stalling the suite.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "shader/preprocess.h"
#include "shader/student_file.h"
#include "test_support.h"
#include "util/error.h"

using namespace pbrlab;
namespace fs = std::filesystem;
using test::CommandRun;
using test::run;

namespace {

// A hostile ndotl.glsl, made in `kit`, and the words every command must say about it.
struct Hostile {
    const char* name;
    void (*make)(const fs::path& kit);
    const char* refusal;
};

const std::string kGoodNdotl = "float ndotl(vec3 N, vec3 L) { return max(dot(N, L), 0.0); }\n";

const Hostile kHostile[] = {
    {"fifo", [](const fs::path& k) { ASSERT_EQ(::mkfifo((k / "ndotl.glsl").c_str(), 0644), 0); },
     "refused: not a regular file (a FIFO)"},
    {"folder", [](const fs::path& k) { fs::create_directory(k / "ndotl.glsl"); },
     "refused: not a regular file (a folder)"},
    {"huge",
     [](const fs::path& k) {
         // 11 MB of valid GLSL comment: only its size is wrong.
         std::ofstream out(k / "ndotl.glsl", std::ios::binary);
         out << kGoodNdotl;
         const std::string line(1023, '/');
         for (int i = 0; i < 11 * 1024; ++i) out << line << '\n';
     },
     "refused: larger than 10 MB"},
    {"nul",
     [](const fs::path& k) {
         std::ofstream(k / "ndotl.glsl", std::ios::binary) << kGoodNdotl << '\0' << "garbage";
     },
     "refused: it contains NUL bytes"},
    {"link-out", [](const fs::path& k) { fs::create_symlink("/etc/hostname", k / "ndotl.glsl"); },
     "refused: it is a link to a file outside the submission folder"},
    {"include-fifo",
     [](const fs::path& k) {
         std::ofstream(k / "ndotl.glsl") << "#include \"helper.glsl\"\n" << kGoodNdotl;
         ASSERT_EQ(::mkfifo((k / "helper.glsl").c_str(), 0644), 0);
     },
     "helper.glsl: refused: not a regular file (a FIFO)"},
};

std::string exe() {
    return "timeout 120 " PBRLAB_EXECUTABLE;
}

}  // namespace

TEST(StudentFiles, ReadStudentFileRefusesEachHostileKindWithoutBlocking) {
    for (const Hostile& h : kHostile) {
        test::TempDir dir;
        const fs::path kit = dir.path / "kit";
        fs::create_directories(kit);
        h.make(kit);
        // The file the student named: for include-fifo the refusal comes from the include.
        const fs::path file =
            std::string(h.name) == "include-fifo" ? kit / "helper.glsl" : kit / "ndotl.glsl";
        EXPECT_NE(screenStudentFile(file, kit).find(
                      std::string(h.refusal).substr(std::string(h.refusal).find("refused"))),
                  std::string::npos)
            << h.name << ": " << screenStudentFile(file, kit);
        EXPECT_THROW(readStudentFile(file, kit), Error) << h.name;
        // Through the preprocessor, as every command reads a step's file.
        ShaderPart part(kit / "ndotl.glsl");
        part.studentFolder = kit;
        try {
            ShaderPreprocessor({kit}).expand({part}, {});
            ADD_FAILURE() << h.name << ": the preprocessor read it";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(h.refusal), std::string::npos)
                << h.name << ": " << e.what();
        }
    }
    // A plain file passes, and its text is what was written.
    test::TempDir dir;
    const fs::path file = dir.write("ndotl.glsl", kGoodNdotl);
    EXPECT_EQ(screenStudentFile(file, dir.path), "");
    EXPECT_EQ(readStudentFile(file, dir.path), kGoodNdotl);
}

TEST(StudentFiles, CheckStabilityRenderAndGradeRefuseEachHostileFileAlike) {
    for (const Hostile& h : kHostile) {
        SCOPED_TRACE(h.name);
        test::TempDir dir;
        const fs::path kit = dir.path / "kit";
        fs::create_directories(kit);
        h.make(kit);
        const std::string k = kit.string();
        // grade: the step fails with the refusal; the report is written.
        const fs::path json = dir.path / "r.json";
        const CommandRun grade =
            run(dir, exe() + " grade " + k + " --steps ndotl --json " + json.string());
        EXPECT_NE(grade.status, 124) << "grade hung:\n" << grade.output;
        EXPECT_NE(grade.output.find(h.refusal), std::string::npos) << grade.output;
        EXPECT_TRUE(fs::exists(json)) << grade.output;
        // check, stability and render say the same words and do not pass.
        for (const std::string& command :
             {" check ndotl --size 32 --submission " + k, " stability ndotl --submission " + k,
              " render ndotl --size 16x16 --submission " + k + " --out " +
                  (dir.path / "x.png").string()}) {
            const CommandRun r = run(dir, exe() + command);
            EXPECT_NE(r.status, 124) << command << " hung:\n" << r.output;
            EXPECT_NE(r.status, 0) << command << " passed:\n" << r.output;
            EXPECT_NE(r.output.find(h.refusal), std::string::npos) << command << "\n" << r.output;
        }
    }
}

// Every compile error a student's file causes points into the student's file, with a hint
// only where the hint is true (Mesa reports some of them in the host's files: a directive at
// common.glsl:1, a redefined main at common.glsl:18, a recursion at 0:0).
TEST(StudentFiles, CompileErrorsCausedByTheStudentsFilePointIntoIt) {
    const std::string body =
        "float lambertCosine(vec3 N, vec3 L)\n{\n    return max(dot(N, L), "
        "0.0)%CALL%;\n}\n";
    struct Case {
        const char* name;
        std::string code;
        const char* location;  // file:line the message must name
        const char* says;      // in the message
        const char* hint;      // in the hint ("" for none)
        const char* notSaid;   // a hint that would be wrong here
    };
    auto with = [&](const std::string& before, const std::string& call, const std::string& after) {
        std::string b = body;
        b.replace(b.find("%CALL%"), 6, call);
        return before + b + after;
    };
    const Case cases[] = {
        {"extension", with("#extension GL_ARB_gpu_shader_fp64 : enable\n", "", ""),
         "ndotl.glsl:1:", "#extension is not allowed in a step's file", "", "recursion"},
        {"line", with("", "", "#line 500 3\n"), "ndotl.glsl:5:", "#line is not allowed", "",
         "recursion"},
        {"main", with("", "", "void main() {}\n"), "ndotl.glsl:5:", "`main' redefined",
         "main is the host's", "contract function you call"},
        {"own recursion",
         with("float f(float x) { return x > 0.0 ? f(x - 1.0) : 0.0; }\n", " + f(0.0)", ""),
         "ndotl.glsl:1:", "recursion", "f calls itself", "contract function"},
        {"cycle of own helpers",
         with("float g(float x);\nfloat f(float x) { return g(x); }\n"
              "float g(float x) { return x > 0.0 ? f(x - 1.0) : 0.0; }\n",
              " + f(0.0)", ""),
         "ndotl.glsl:", "recursion", "cycle of calls", "contract function"},
        // pow reaches the program as pbrlab_definedPow (preprocess.cpp): messages say pow.
        {"pow misused", with("", " + pow(1.0)", ""), "ndotl.glsl:3:", "pow(float)", "",
         "pbrlab_definedPow"},
        {"pow redefined", with("#define pow(x, y) x\n", "", ""),
         "ndotl.glsl:1:", "#define pow: pow is a macro of the host's", "", "pbrlab_definedPow"},
        // Right where the grader draws points alone, half Lambert in every picture: the host's
        // own macros say how it draws, so no file may test them.
        {"host's macro tested",
         "float lambertCosine(vec3 N, vec3 L)\n{\n#ifdef PBRLAB_PROBE\n"
         "    return max(dot(N, L), 0.0);\n#else\n    return 0.5 * dot(N, L) + 0.5;\n#endif\n}\n",
         "ndotl.glsl:3:", "PBRLAB_PROBE is one of the host's own macros", "", "recursion"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        test::TempDir dir;
        const fs::path kit = dir.path / "kit";
        fs::create_directories(kit);
        std::ofstream(kit / "ndotl.glsl") << c.code;
        const CommandRun r =
            run(dir, exe() + " check ndotl --size 32 --submission " + kit.string());
        EXPECT_NE(r.status, 0) << r.output;
        EXPECT_NE(r.output.find((kit / c.location).string()), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(c.says), std::string::npos) << r.output;
        if (*c.hint) {
            EXPECT_NE(r.output.find(c.hint), std::string::npos) << r.output;
        }
        EXPECT_EQ(r.output.find(c.notSaid), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("common.glsl"), std::string::npos) << r.output;
    }
}

// A later step's function is not in a step's program (so no recursion through a contract
// function can exist): calling one names the step that introduces it, at the student's call,
// not Mesa's "no function with name" in common.glsl. The case: fresnel written with
// split_sum's helper.
TEST(StudentFiles, ALaterStepsFunctionIsNamedWithTheStepThatIntroducesIt) {
    struct Case {
        const char* file;
        const char* code;
        const char* says;
    };
    const Case cases[] = {
        {"fresnel.glsl",
         "vec3 fresnelSchlick(float cosTheta, vec3 F0)\n{\n"
         "    return fresnelSchlickRoughness(cosTheta, F0, 0.0);\n}\n",
         "fresnelSchlickRoughness is introduced in step 21 (split_sum); fresnel cannot call it"},
        {"specular.glsl",
         "vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)\n{\n"
         "    return cookTorranceBRDF(N, V, L, F0, 1.0, roughness);\n}\n",
         "cookTorranceBRDF is introduced in step 11 (brdf); specular cannot call it"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.file);
        test::TempDir dir;
        const fs::path kit = dir.path / "kit";
        fs::create_directories(kit);
        std::ofstream(kit / c.file) << c.code;
        const std::string id = fs::path(c.file).stem().string();
        const CommandRun r =
            run(dir, exe() + " check " + id + " --size 32 --submission " + kit.string());
        EXPECT_NE(r.status, 0) << r.output;
        EXPECT_NE(r.output.find((kit / c.file).string() + ":3: error: " + c.says),
                  std::string::npos)
            << r.output;
        EXPECT_EQ(r.output.find("common.glsl"), std::string::npos) << r.output;
    }
}
