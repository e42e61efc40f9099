#include "util/cache_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <functional>
#include <thread>

#include "util/digest.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

std::uint64_t digestOf(const char* data, size_t begin, size_t end) {
    Digest digest;
    digest.add(data + begin, end - begin);
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
