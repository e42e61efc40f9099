#include <gtest/gtest.h>

#include "steps/plugin_host.h"
#include "test_support.h"
#include "util/error.h"

using namespace pbrlab;
namespace fs = std::filesystem;

TEST(Plugins, LoadsTheBuiltModulesInStepOrder) {
    ModuleRegistry registry(PBRLAB_MODULE_DIR);
    EXPECT_TRUE(registry.failures().empty());
    ASSERT_FALSE(registry.modules().empty());
    for (size_t i = 1; i < registry.modules().size(); ++i)
        EXPECT_LT(registry.modules()[i - 1].desc->step, registry.modules()[i].desc->step);
    const LoadedModule& ndotl = registry.find("ndotl");
    EXPECT_EQ(ndotl.desc->function, "float lambertCosine(vec3 N, vec3 L)");
    EXPECT_TRUE(fs::exists(ndotl.sourceDir / "solution.glsl"));
}

TEST(Plugins, BrokenModulesAreReportedAndTheOthersStillLoad) {
    test::TempDir dir;
    for (const auto& e : fs::directory_iterator(PBRLAB_BROKEN_MODULE_DIR))
        fs::copy(e.path(), dir.path / e.path().filename());
    fs::copy(fs::path(PBRLAB_MODULE_DIR) / "pbrlab-ndotl.so", dir.path / "pbrlab-ndotl.so");
    fs::copy(fs::path(PBRLAB_MODULE_DIR) / "pbrlab-ndotl.so", dir.path / "pbrlab-no_step.so");
    dir.write("pbrlab-f0.so", "this is not an ELF file");

    ModuleRegistry registry(dir.path);
    ASSERT_EQ(registry.modules().size(), 1u);
    EXPECT_EQ(registry.modules()[0].desc->id, "ndotl");
    ASSERT_EQ(registry.failures().size(), 5u);
    std::map<std::string, std::string> reasons;
    for (const auto& f : registry.failures()) reasons[f.library.filename().string()] = f.reason;
    EXPECT_NE(reasons["pbrlab-g1.so"].find("ABI version"), std::string::npos);
    EXPECT_NE(reasons["pbrlab-smith.so"].find("not a pbrlab module"), std::string::npos);
    EXPECT_NE(reasons["pbrlab-ndf.so"].find("differs from the contract"), std::string::npos);
    EXPECT_NE(reasons["pbrlab-f0.so"].find("cannot load"), std::string::npos);
    EXPECT_NE(reasons["pbrlab-no_step.so"].find("no step folder declares 'no_step'"),
              std::string::npos);
}

TEST(Plugins, UnknownIdListsTheLoadedOnes) {
    ModuleRegistry registry(PBRLAB_MODULE_DIR);
    try {
        registry.find("nope");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("ndotl"), std::string::npos);
    }
}

TEST(Plugins, MissingDirectoryIsAClearError) {
    EXPECT_THROW(ModuleRegistry("/nonexistent/modules"), Error);
}

// A step from outside the tree: a folder of libraries holding the step folder too (what
// pbrlab_add_step makes). Here the ndotl library under another id, inserted after ndotl by its
// order key: it loads with the identity its step.json gives, at its position, and every step
// after it moves down one without any change to their folders.
TEST(Plugins, AStepFromAnotherFolderLoadsAtItsDeclaredPosition) {
    test::TempDir dir;
    fs::copy(fs::path(PBRLAB_MODULE_DIR) / "pbrlab-ndotl.so", dir.path / "pbrlab-lambert_again.so");
    const fs::path ndotl = fs::path(PBRLAB_SOURCE_DIR) / "labs" / "ndotl";
    fs::create_directories(dir.path / "lambert_again");
    for (const char* file : {"solution.glsl", "view.glsl", "README.md"})
        fs::copy(ndotl / file, dir.path / "lambert_again" / file);
    dir.write("lambert_again/step.json",
              R"j({"id": "lambert_again", "lab": "direct", "order": 45,
                  "function": "float lambertAgain(vec3 N, vec3 L)"})j");
    ModuleRegistry registry(std::vector<fs::path>{PBRLAB_MODULE_DIR, dir.path});
    EXPECT_TRUE(registry.failures().empty());
    const LoadedModule& added = registry.find("lambert_again");
    EXPECT_EQ(added.desc->step, 5);
    EXPECT_EQ(added.desc->lab, "direct");
    EXPECT_EQ(added.sourceDir, dir.path / "lambert_again");
    EXPECT_EQ(registry.find("ndotl").desc->step, 4);
    EXPECT_EQ(registry.find("ndf").desc->step, 6);
    EXPECT_EQ(registry.modules()[4].desc->id, "lambert_again");
}
