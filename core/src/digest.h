// A 64-bit digest of bytes (FNV-1a over 64-bit words): stable across runs and compilers,
// unlike std::hash, so it can name what a disk cache holds; and the build IDs that name the
// code a cached value came from. Not cryptographic: it tells inputs apart, it does not resist
// an adversary (the cache is the grader's own folder).
#pragma once

#include <elf.h>
#include <link.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <type_traits>
#include <vector>

namespace pbrlab {

struct Digest {
    std::uint64_t h = 1469598103934665603ull;
    void add(const void* data, size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        std::uint64_t word = 0;
        size_t i = 0;
        for (; i + 8 <= bytes; i += 8) {
            std::memcpy(&word, p + i, 8);
            h = (h ^ word) * 1099511628211ull;
        }
        for (; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
        // The length too, so that "ab" + "c" and "a" + "bc" differ.
        h = (h ^ bytes) * 1099511628211ull;
    }
    void add(const std::string& s) { add(s.data(), s.size()); }
    // Numbers and plain arrays of them (doubles, glm vectors): their bytes.
    template <class T,
              class = std::enable_if_t<std::is_trivially_copyable_v<T> && !std::is_pointer_v<T>>>
    void add(const T& value) {
        add(&value, sizeof value);
    }
    std::string hex() const {
        char text[17];
        std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
        return text;
    }
};

// The GNU build IDs of the program itself ("") and of loaded libraries named by file name, in
// that order: what identifies the code that computed a cached value (any rebuild changes its
// ID). Empty when one is missing: then nothing is cached.
inline std::string buildIds(const std::vector<std::string>& names) {
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
