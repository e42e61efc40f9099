// The tests' caches are their own, never the user's home (issue 22): pbrlab's IBL cache, Mesa's
// shader cache and whatever else follows XDG_CACHE_HOME (fontconfig under the GUI tests) go to
// test-caches/ beside this executable. Set before any test runs, so every GL context of this
// process and every pbrlab process a test starts inherits them; a variable the caller set wins
// (`PBRLAB_CACHE=/tmp/mine build/tests/pbrlab_tests`). ctest empties the folder at the start of
// each run (the fixture TestCaches.Clear, tests/CMakeLists.txt), so no run reads what an earlier
// one left. XDG_CONFIG_HOME is left alone: the GUI tests give each run a HOME of its own and
// read its remembered state there.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <string>

#include "test_support.h"

namespace fs = std::filesystem;

namespace {

const fs::path kCaches = fs::read_symlink("/proc/self/exe").parent_path() / "test-caches";

const bool kCachesSet = [] {
    for (const auto& [variable, folder] : {std::pair{"PBRLAB_CACHE", "pbrlab"},
                                           {"MESA_SHADER_CACHE_DIR", "mesa"},
                                           {"XDG_CACHE_HOME", "xdg-cache"}}) {
        fs::create_directories(kCaches / folder);
        setenv(variable, (kCaches / folder).c_str(), 0);
    }
    return true;
}();

}  // namespace

// A pbrlab process started by a test, with HOME an empty folder, leaves that folder empty: an
// environment-lit step (the IBL cache) rendered through a fresh GL context (Mesa's cache).
TEST(TestCaches, AStartedPbrlabWritesNothingInTheHomeFolder) {
    ASSERT_TRUE(kCachesSet);
    pbrlab::test::TempDir home, out;
    const pbrlab::test::CommandRun r =
        pbrlab::test::run(out, "HOME=" + home.path.string() +
                                   " " PBRLAB_EXECUTABLE " render split_sum --size 32x32 --out " +
                                   (out.path / "s.png").string());
    ASSERT_EQ(r.status, 0) << r.output;
    ASSERT_TRUE(fs::exists(out.path / "s.png"));
    std::string written;
    for (const auto& e : fs::recursive_directory_iterator(home.path))
        written += e.path().string() + "\n";
    EXPECT_TRUE(written.empty()) << "written in HOME:\n" << written;
}
