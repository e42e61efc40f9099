// util/digest.h's buildIds on Linux: the NT_GNU_BUILD_ID notes of the program and its loaded
// libraries, read from their program headers with dl_iterate_phdr.
#include <elf.h>
#include <link.h>

#include <cstdio>
#include <cstring>
#include <filesystem>

#include "util/digest.h"

namespace pbrlab {

// The GNU build IDs of the program itself ("") and of loaded libraries named by file name, in
// that order: what identifies the code that computed a cached value (any rebuild changes its
// ID). Empty when one is missing: then nothing is cached.
std::string buildIds(const std::vector<std::string>& names) {
    struct Search {
        const std::vector<std::string>& names;
        std::vector<std::string> ids;
        bool program = true;  // dl_iterate_phdr reports the program first
    } search{names, std::vector<std::string>(names.size())};
    dl_iterate_phdr(
        [](dl_phdr_info* info, size_t, void* data) {
            Search& s = *static_cast<Search*>(data);
            const std::string name =
                s.program ? ""
                          : std::filesystem::path(info->dlpi_name ? info->dlpi_name : "")
                                .filename()
                                .string();
            s.program = false;
            for (size_t k = 0; k < s.names.size(); ++k) {
                if (s.names[k] != name || !s.ids[k].empty()) continue;
                for (int i = 0; i < info->dlpi_phnum; ++i) {
                    const ElfW(Phdr)& segment = info->dlpi_phdr[i];
                    if (segment.p_type != PT_NOTE) continue;
                    const size_t align = segment.p_align == 8 ? 8 : 4;
                    auto padded = [&](size_t n) { return (n + align - 1) / align * align; };
                    const char* p =
                        reinterpret_cast<const char*>(info->dlpi_addr + segment.p_vaddr);
                    const char* end = p + segment.p_memsz;
                    while (p + sizeof(ElfW(Nhdr)) <= end) {
                        const auto* note = reinterpret_cast<const ElfW(Nhdr)*>(p);
                        const char* owner = p + sizeof(ElfW(Nhdr));
                        const auto* desc =
                            reinterpret_cast<const unsigned char*>(owner + padded(note->n_namesz));
                        if (reinterpret_cast<const char*>(desc) + note->n_descsz > end) break;
                        if (note->n_type == NT_GNU_BUILD_ID && note->n_namesz == 4 &&
                            std::memcmp(owner, "GNU", 4) == 0)
                            for (unsigned b = 0; b < note->n_descsz; ++b) {
                                char hex[3];
                                std::snprintf(hex, sizeof hex, "%02x", desc[b]);
                                s.ids[k] += hex;
                            }
                        p = reinterpret_cast<const char*>(desc) + padded(note->n_descsz);
                    }
                }
            }
            return 0;
        },
        &search);
    std::string all;
    for (const std::string& id : search.ids) {
        if (id.empty()) return "";
        all += id + " ";
    }
    return all;
}

}  // namespace pbrlab
