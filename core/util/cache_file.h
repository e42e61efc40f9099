// The files of pbrlab's disk cache (IBL maps, converged integrals, grading G-buffers, generated
// environments): an 8-byte magic naming the format, the payload, then a digest of the payload.
// Written to a temporary file and renamed over the name, so a reader sees the whole file or
// none; a torn, damaged or foreign file reads as absent (its value is computed again), never as
// values.
#pragma once

#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace pbrlab {

class CacheWriter {
public:
    explicit CacheWriter(const char (&magic)[8]) : payload_(magic, 8) {}
    void bytes(const void* data, size_t size) {
        payload_.append(static_cast<const char*>(data), size);
    }
    template <class T, class = std::enable_if_t<std::is_trivially_copyable_v<T>>>
    void put(const T& value) {
        bytes(&value, sizeof value);
    }
    // False when the file could not be written (then nothing is left behind: no cache, fine).
    bool commit(const std::filesystem::path& file) const;

private:
    std::string payload_;  // the magic, then the payload
};

class CacheReader {
public:
    // Reads `file` whole; ok() only when it has this magic and its digest matches.
    CacheReader(const std::filesystem::path& file, const char (&magic)[8]);
    bool ok() const { return ok_; }
    // False past the end of the payload (or when not ok()).
    bool bytes(void* data, size_t size) {
        if (!ok_ || size > end_ - at_) return false;
        std::memcpy(data, payload_.get() + at_, size);
        at_ += size;
        return true;
    }
    // `count` floats into `out` (replacing what it held): written once, not zeroed first.
    bool floats(std::vector<float>& out, size_t count) {
        if (!ok_ || count > (end_ - at_) / sizeof(float)) return false;
        out.resize(0);
        out.reserve(count);
        const char* p = payload_.get() + at_;
        for (size_t i = 0; i < count; ++i, p += sizeof(float)) {
            float f;
            std::memcpy(&f, p, sizeof f);
            out.push_back(f);
        }
        at_ += count * sizeof(float);
        return true;
    }
    template <class T, class = std::enable_if_t<std::is_trivially_copyable_v<T>>>
    bool get(T& value) {
        return bytes(&value, sizeof value);
    }
    bool atEnd() const { return ok_ && at_ == end_; }

private:
    std::unique_ptr<char[]> payload_;  // the whole file, as read (not zeroed first)
    size_t at_ = 8, end_ = 0;
    bool ok_ = false;
};

}  // namespace pbrlab
