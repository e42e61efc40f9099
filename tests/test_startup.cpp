// Start-up: no program pays for OpenImageIO unless a file needs it (core/assets/image_codecs.h),
// and a command about one module opens only that module's library.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "native/huge_pages.h"
#include "steps/plugin_host.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;
using test::CommandRun;
using test::run;

namespace {

// The environment of a command that cannot open libpbrlab_oiio.so (so cannot use OpenImageIO).
std::string withoutOpenImageIo(const test::TempDir& dir) {
    return "PBRLAB_OIIO_LIBRARY=" + (dir.path / "missing-libpbrlab_oiio.so").string() + " ";
}

}  // namespace

TEST(Startup, NoProgramLinksOpenImageIo) {
    // ldd lists every library the dynamic linker loads before main, dependencies included.
    test::TempDir dir;
    const std::string tests = fs::read_symlink("/proc/self/exe").string();
    for (const std::string& program : {std::string(PBRLAB_EXECUTABLE), tests}) {
        const CommandRun r = run(dir, "ldd " + program);
        ASSERT_EQ(r.status, 0) << r.output;
        EXPECT_NE(r.output.find("libstdc++"), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find("OpenImageIO"), std::string::npos) << program << "\n" << r.output;
    }
    // OpenImageIO went into pbrlab's own library, built where the core looks for it first.
    const fs::path library = fs::path(PBRLAB_EXECUTABLE).parent_path() / "libpbrlab_oiio.so";
    const CommandRun r = run(dir, "ldd " + library.string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("OpenImageIO"), std::string::npos) << r.output;
}

TEST(Startup, PngAndExrOutNeedNoOpenImageIo) {
    test::TempDir dir;
    const std::string env = withoutOpenImageIo(dir);
    for (const char* out : {"n.png", "n.exr"}) {
        const CommandRun r = run(dir, env + PBRLAB_EXECUTABLE " render ndotl --size 32x32 --out " +
                                          (dir.path / out).string());
        EXPECT_EQ(r.status, 0) << r.output;
        EXPECT_TRUE(fs::exists(dir.path / out)) << out;
    }
    // 8- and 16-bit PNGs, sRGB and linear.
    const CommandRun r = run(dir, env + PBRLAB_EXECUTABLE " textures --size 16 --out " +
                                      (dir.path / "textures").string());
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir.path / "textures" / "roughness.png"));
}

TEST(Startup, AMissingOpenImageIoLibraryIsAClearError) {
    // Writing Radiance HDR is OpenImageIO's.
    test::TempDir dir;
    const CommandRun r =
        run(dir, withoutOpenImageIo(dir) + PBRLAB_EXECUTABLE " environment --width 16 --out " +
                     (dir.path / "sky.hdr").string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("sky.hdr"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("libpbrlab_oiio.so"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("missing-libpbrlab_oiio.so"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.path / "sky.hdr"));
}

TEST(Startup, ACommandAboutOneModuleOpensOnlyItsLibrary) {
    ModuleRegistry one(PBRLAB_MODULE_DIR, "ndotl");
    ASSERT_EQ(one.modules().size(), 1u);
    EXPECT_EQ(one.find("ndotl").desc->id, "ndotl");
    // An id no library is named for opens them all, so the error can list what there is.
    ModuleRegistry all(PBRLAB_MODULE_DIR);
    ModuleRegistry unknown(PBRLAB_MODULE_DIR, "no_such_step");
    EXPECT_GT(all.modules().size(), 1u);
    EXPECT_EQ(unknown.modules().size(), all.modules().size());
    try {
        unknown.find("no_such_step");
        FAIL() << "found a module that does not exist";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("ndotl"), std::string::npos) << e.what();
    }
}

// pbrlab restarts itself once with glibc's malloc asking for huge pages, where the kernel gives
// them on request only, and never overrides a setting the user made.
TEST(Startup, HugePagesAreAskedForOnceWhereTheKernelWaitsToBeAsked) {
    const char* render[] = {"pbrlab", "render", "ndotl"};
    const char* help[] = {"pbrlab", "grade", "--help"};
    auto madvise = [] { return std::string("always [madvise] never"); };
    EXPECT_EQ(hugePageTunables(nullptr, 3, render, madvise), "glibc.malloc.hugetlb=1");
    EXPECT_EQ(hugePageTunables("", 3, render, madvise), "glibc.malloc.hugetlb=1");
    EXPECT_EQ(hugePageTunables("glibc.malloc.check=0", 3, render, madvise),
              "glibc.malloc.check=0:glibc.malloc.hugetlb=1");
    // Already asked (the restarted process itself), or kept small by the user.
    EXPECT_EQ(hugePageTunables("glibc.malloc.hugetlb=1", 3, render, madvise), "");
    EXPECT_EQ(hugePageTunables("glibc.malloc.hugetlb=0", 3, render, madvise), "");
    // The kernel decides alone, or there are no huge pages.
    EXPECT_EQ(
        hugePageTunables(nullptr, 3, render, [] { return std::string("[always] madvise never"); }),
        "");
    EXPECT_EQ(
        hugePageTunables(nullptr, 3, render, [] { return std::string("always madvise [never]"); }),
        "");
    EXPECT_EQ(hugePageTunables(nullptr, 3, render, [] { return std::string(); }), "");
    // Help costs nothing more: not even a read of the kernel's policy.
    auto unread = [] {
        ADD_FAILURE() << "the policy was read for --help";
        return std::string("always [madvise] never");
    };
    EXPECT_EQ(hugePageTunables(nullptr, 3, help, unread), "");
    EXPECT_EQ(hugePageTunables("glibc.malloc.hugetlb=0", 3, render, unread), "");
}

TEST(Startup, StatsSayWhichPagesTheProcessUses) {
    std::ifstream policyFile("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string policy;
    std::getline(policyFile, policy);
    if (policy.find("[madvise]") == std::string::npos)
        GTEST_SKIP() << "the kernel's huge-page policy is not madvise: " << policy;
    test::TempDir dir;
    const std::string command = std::string(PBRLAB_EXECUTABLE) +
                                " render ndotl --size 16x16 --out " +
                                (dir.path / "x.png").string() + " --stats";
    const CommandRun asked = run(dir, "env -u GLIBC_TUNABLES " + command);
    ASSERT_EQ(asked.status, 0) << asked.output;
    EXPECT_NE(asked.output.find("memory pages: huge (glibc.malloc.hugetlb=1)"), std::string::npos)
        << asked.output;
    const CommandRun kept = run(dir, "env GLIBC_TUNABLES=glibc.malloc.hugetlb=0 " + command);
    ASSERT_EQ(kept.status, 0) << kept.output;
    EXPECT_NE(kept.output.find("memory pages: small"), std::string::npos) << kept.output;
}
