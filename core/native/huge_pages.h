// Large pages for pbrlab's own memory, on Linux where the kernel grants transparent huge pages
// only to memory that asks for them (THP "madvise", Debian's default).
#pragma once

#include <string>

namespace pbrlab {

// Restarts this process once, before it has done any work, with glibc's malloc asking for
// transparent huge pages (GLIBC_TUNABLES=glibc.malloc.hugetlb=1), and returns only when it did
// not restart. Why: a render or a grade fills tens of megabytes of fresh memory (llvmpipe's
// textures and framebuffers, the maps), and each 4 KiB page costs the kernel a fault when first
// touched; 2 MiB pages take 512 times fewer (docs/speed.md, "Huge pages"). glibc reads the
// setting only at start-up, hence the restart. Child processes inherit it.
void restartWithHugePages(int argc, char** argv);

// The GLIBC_TUNABLES value to restart with, or "" to go on as is: when `tunables` (the
// variable's value, null if unset) already names the setting (glibc.malloc.hugetlb=0 keeps
// small pages), for --help and --version, and when the kernel's policy (`kernelPolicy()`, the
// first line of /sys/kernel/mm/transparent_hugepage/enabled, read only if those do not answer)
// gives huge pages to every process or to none.
std::string hugePageTunables(const char* tunables, int argc, const char* const* argv,
                             std::string (*kernelPolicy)());

// What --stats says of this process's pages: "huge (glibc.malloc.hugetlb=1)" or "small".
std::string memoryPagesDescription();

}  // namespace pbrlab
