#include "util/cache_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <thread>

#include "util/digest.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

// The checksum of a file's payload: FNV-1a on four interleaved lanes of 64-bit words, folded
// into one Digest. One lane is a chain of dependent multiplies (about 2 GB/s); four run side by
// side, and a grading process checks a few hundred megabytes of cached maps.
std::uint64_t digestOf(const char* data, size_t begin, size_t end) {
    constexpr std::uint64_t kPrime = 1099511628211ull;
    const std::uint64_t basis = Digest{}.h;
    std::uint64_t lanes[4] = {basis, basis ^ 1, basis ^ 2, basis ^ 3};
    const char* p = data + begin;
    const size_t bytes = end - begin;
    size_t i = 0;
    for (; i + 32 <= bytes; i += 32) {
        for (int lane = 0; lane < 4; ++lane) {
            std::uint64_t word = 0;
            std::memcpy(&word, p + i + 8 * size_t(lane), 8);
            lanes[lane] = (lanes[lane] ^ word) * kPrime;
        }
    }
    Digest digest;
    digest.add(lanes);
    digest.add(p + i, bytes - i);  // the last bytes, fewer than 32
    digest.add(bytes);
    return digest.h;
}

}  // namespace

bool CacheWriter::commit(const fs::path& file) const {
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);
    // Per process and thread: the GUI's window and evaluation thread may write the same file.
    const fs::path tmp = file.string() + ".tmp" + std::to_string(::getpid()) + "-" +
                         std::to_string(std::hash<std::thread::id>()(std::this_thread::get_id()));
    {
        std::ofstream out(tmp, std::ios::binary);
        const std::uint64_t digest = digestOf(payload_.data(), 8, payload_.size());
        out.write(payload_.data(), std::streamsize(payload_.size()));
        out.write(reinterpret_cast<const char*>(&digest), sizeof digest);
        if (!out) {
            fs::remove(tmp, ec);
            return false;
        }
    }
    fs::rename(tmp, file, ec);  // atomic: a reader sees the whole file or none
    if (ec) fs::remove(tmp, ec);
    return !ec;
}

CacheReader::CacheReader(const fs::path& file, const char (&magic)[8]) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    struct stat status {};
    if (::fstat(fd, &status) == 0 && status.st_size >= off_t(8 + sizeof(std::uint64_t))) {
        void* mapped = ::mmap(nullptr, size_t(status.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
        if (mapped != MAP_FAILED) {
            payload_ = static_cast<const char*>(mapped);
            size_ = size_t(status.st_size);
        }
    }
    ::close(fd);
    if (!payload_ || std::memcmp(payload_, magic, 8) != 0) return;
    end_ = size_ - sizeof(std::uint64_t);
    std::uint64_t stored = 0;
    std::memcpy(&stored, payload_ + end_, sizeof stored);
    ok_ = stored == digestOf(payload_, 8, end_);
}

CacheReader::~CacheReader() {
    if (payload_) ::munmap(const_cast<char*>(payload_), size_);
}

}  // namespace pbrlab
