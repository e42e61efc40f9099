#include "native/huge_pages.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>

namespace pbrlab {
namespace {

constexpr const char* kTunables = "GLIBC_TUNABLES";
constexpr const char* kHugePages = "glibc.malloc.hugetlb=1";

std::string kernelPolicy() {
    std::ifstream policy("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    std::getline(policy, line);
    return line;
}

}  // namespace

std::string hugePageTunables(const char* tunables, int argc, const char* const* argv,
                             std::string (*kernelPolicy)()) {
    if (tunables && std::strstr(tunables, "glibc.malloc.hugetlb")) return {};
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help") ||
            !std::strcmp(argv[i], "--version"))
            return {};
    }
    // "always [madvise] never": the bracketed word is the policy in force.
    if (kernelPolicy().find("[madvise]") == std::string::npos) return {};
    return tunables && *tunables ? std::string(tunables) + ":" + kHugePages
                                 : std::string(kHugePages);
}

void restartWithHugePages(int argc, char** argv) {
#if defined(__linux__) && defined(__GLIBC__)
    const std::string value = hugePageTunables(std::getenv(kTunables), argc, argv, &kernelPolicy);
    if (value.empty()) return;
    // Run by a loader (ld-linux.so pbrlab ...), /proc/self/exe is the loader, not pbrlab.
    char self[4096] = {};
    const ssize_t length = readlink("/proc/self/exe", self, sizeof self - 1);
    if (length <= 0 || std::strstr(self, "/ld-")) return;
    if (setenv(kTunables, value.c_str(), 1) != 0) return;
    execv(self, argv);
    // Still here: the restart failed. Go on with small pages; the setting stays in the
    // environment, so child processes do not try again.
#else
    (void)argc;
    (void)argv;
#endif
}

std::string memoryPagesDescription() {
    const char* tunables = std::getenv(kTunables);
    const std::string policy = kernelPolicy();
    if (tunables && std::strstr(tunables, kHugePages) &&
        policy.find("[never]") == std::string::npos)
        return std::string("huge (") + kHugePages + ")";
    return policy.find("[always]") != std::string::npos ? "huge (the kernel's default)" : "small";
}

}  // namespace pbrlab
