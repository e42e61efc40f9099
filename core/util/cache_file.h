// The files of pbrlab's disk cache (IBL maps, converged integrals, grading G-buffers, generated
// environments): an 8-byte magic naming the format, the payload, then a digest of the payload.
// Written to a temporary file and renamed over the name, so a reader sees the whole file or
// none; a torn, damaged or foreign file reads as absent (its value is computed again), never as
// values.
#pragma once

#include <cstring>
#include <filesystem>
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
    // Maps `file` (read-only, private); ok() only when it has this magic and its digest
    // matches. Mapped, not read: the files are megabytes (a sun's sky is 25 MB), and a read
    // copies them into fresh memory that each process pays page faults for. Safe against the
    // writers, which rename a whole new file over the name and never change one in place.
    CacheReader(const std::filesystem::path& file, const char (&magic)[8]);
    ~CacheReader();
    CacheReader(const CacheReader&) = delete;
    CacheReader& operator=(const CacheReader&) = delete;
    bool ok() const { return ok_; }
    // False past the end of the payload (or when not ok()).
    bool bytes(void* data, size_t size) {
        if (!ok_ || size > end_ - at_) return false;
        std::memcpy(data, payload_ + at_, size);
        at_ += size;
        return true;
    }
    // `count` floats into `out` (replacing what it held).
    bool floats(std::vector<float>& out, size_t count) {
        if (!ok_ || count > (end_ - at_) / sizeof(float)) return false;
        out.resize(count);
        std::memcpy(out.data(), payload_ + at_, count * sizeof(float));
        at_ += count * sizeof(float);
        return true;
    }
    template <class T, class = std::enable_if_t<std::is_trivially_copyable_v<T>>>
    bool get(T& value) {
        return bytes(&value, sizeof value);
    }
    bool atEnd() const { return ok_ && at_ == end_; }

private:
    const char* payload_ = nullptr;  // the whole file, mapped
    size_t size_ = 0;
    size_t at_ = 8, end_ = 0;
    bool ok_ = false;
};

}  // namespace pbrlab
