// A 64-bit digest of bytes (FNV-1a over 64-bit words): stable across runs and compilers,
// unlike std::hash, so it can name what a disk cache holds; and the build IDs that name the
// code a cached value came from. Not cryptographic: it tells inputs apart, it does not resist
// an adversary (the cache is the grader's own folder).
#pragma once

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

// The build IDs of the program itself ("") and of loaded libraries named by file name, in that
// order: what identifies the code that computed a cached value (any rebuild changes its ID).
// Empty when one is missing: then nothing is cached. Defined by the platform (core/native:
// the GNU build-ID notes of the loaded ELF files).
std::string buildIds(const std::vector<std::string>& names);

}  // namespace pbrlab
