#include <gtest/gtest.h>

#include "pbrlab/error.h"
#include "plugins.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {
std::string labs() {
    return std::string(PBRLAB_SOURCE_DIR) + "/labs";
}
}  // namespace

TEST(Plugins, LoadsTheBuiltModulesInStepOrder) {
    ModuleRegistry registry(PBRLAB_MODULE_DIR, labs());
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
    fs::copy(fs::path(PBRLAB_MODULE_DIR) / "pbrlab-04-ndotl.so", dir.path / "pbrlab-04-ndotl.so");
    dir.write("pbrlab-96-garbage.so", "this is not an ELF file");

    ModuleRegistry registry(dir.path, labs());
    ASSERT_EQ(registry.modules().size(), 1u);
    EXPECT_EQ(registry.modules()[0].desc->id, "ndotl");
    ASSERT_EQ(registry.failures().size(), 4u);
    std::map<std::string, std::string> reasons;
    for (const auto& f : registry.failures()) reasons[f.library.filename().string()] = f.reason;
    EXPECT_NE(reasons["pbrlab-99-wrong-abi.so"].find("ABI version"), std::string::npos);
    EXPECT_NE(reasons["pbrlab-98-not-a-module.so"].find("not a pbrlab module"), std::string::npos);
    EXPECT_NE(reasons["pbrlab-97-bad-contract.so"].find("differs from the contract"),
              std::string::npos);
    EXPECT_NE(reasons["pbrlab-96-garbage.so"].find("cannot load"), std::string::npos);
}

TEST(Plugins, UnknownIdListsTheLoadedOnes) {
    ModuleRegistry registry(PBRLAB_MODULE_DIR, labs());
    try {
        registry.find("nope");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("ndotl"), std::string::npos);
    }
}

TEST(Plugins, MissingDirectoryIsAClearError) {
    EXPECT_THROW(ModuleRegistry("/nonexistent/modules", labs()), Error);
}
