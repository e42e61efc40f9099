#include "util/cache_file.h"

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
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    if (!in) return;
    // One read of the whole size: the files are megabytes (a sun's sky is 25 MB), which a
    // character iterator copies a byte at a time.
    const std::streamoff size = in.tellg();
    if (size < std::streamoff(8 + sizeof(std::uint64_t))) return;
    // Uninitialised (the read overwrites it); not make_unique_for_overwrite, which the page's
    // C++ library (Emscripten's libc++) does not have.
    payload_.reset(new char[size_t(size)]);
    in.seekg(0);
    if (!in.read(payload_.get(), size) || std::memcmp(payload_.get(), magic, 8) != 0) return;
    end_ = size_t(size) - sizeof(std::uint64_t);
    std::uint64_t stored = 0;
    std::memcpy(&stored, payload_.get() + end_, sizeof stored);
    ok_ = stored == digestOf(payload_.get(), 8, end_);
}

}  // namespace pbrlab
