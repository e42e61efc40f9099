#include "util/fs.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>

#include "util/error.h"

namespace fs = std::filesystem;

namespace pbrlab {

std::string readFile(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw Error(file.string() + ": cannot read it");
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool isInside(const fs::path& path, const fs::path& root) {
    std::error_code ec1, ec2;
    fs::path p = fs::weakly_canonical(path, ec1), r = fs::weakly_canonical(root, ec2);
    if (ec1 || ec2) return false;
    auto [rootEnd, _] = std::mismatch(r.begin(), r.end(), p.begin(), p.end());
    return rootEnd == r.end();
}

FileStamp FileStamp::of(const fs::path& file) {
    FileStamp stamp;
    std::error_code ec;
    const fs::file_time_type time = fs::last_write_time(file, ec);
    if (ec) return stamp;
    stamp.time = time;
    if (!fs::is_regular_file(file, ec)) return stamp;
    std::ifstream in(file, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    stamp.size = bytes.size();
    stamp.hash = std::hash<std::string>{}(bytes);
    return stamp;
}

}  // namespace pbrlab
