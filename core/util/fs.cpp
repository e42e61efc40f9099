#include "util/fs.h"

#include <algorithm>

namespace fs = std::filesystem;

namespace pbrlab {

bool isInside(const fs::path& path, const fs::path& root) {
    std::error_code ec1, ec2;
    fs::path p = fs::weakly_canonical(path, ec1), r = fs::weakly_canonical(root, ec2);
    if (ec1 || ec2) return false;
    auto [rootEnd, _] = std::mismatch(r.begin(), r.end(), p.begin(), p.end());
    return rootEnd == r.end();
}

}  // namespace pbrlab
