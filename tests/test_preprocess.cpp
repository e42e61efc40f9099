#include <gtest/gtest.h>

#include "pbrlab/error.h"
#include "shader/preprocess.h"
#include "test_support.h"

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
    EXPECT_EQ(s.text.find("float c()"), s.text.rfind("float c()"));
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
}
