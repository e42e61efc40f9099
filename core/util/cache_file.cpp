#include "util/cache_file.h"

#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <functional>
#include <iterator>
#include <thread>

#include "util/digest.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

std::uint64_t digestOf(const std::string& text, size_t begin, size_t end) {
    Digest digest;
    digest.add(text.data() + begin, end - begin);
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
        const std::uint64_t digest = digestOf(payload_, 8, payload_.size());
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
    std::ifstream in(file, std::ios::binary);
    if (!in) return;
    payload_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (payload_.size() < 8 + sizeof(std::uint64_t) || payload_.compare(0, 8, magic, 8) != 0)
        return;
    end_ = payload_.size() - sizeof(std::uint64_t);
    std::uint64_t stored = 0;
    std::memcpy(&stored, payload_.data() + end_, sizeof stored);
    ok_ = stored == digestOf(payload_, 8, end_);
}

}  // namespace pbrlab
