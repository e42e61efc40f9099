// Paths on disk.
#pragma once

#include <filesystem>

namespace pbrlab {

// True when `path` (made canonical) lies inside `root` (made canonical). A path that cannot be
// resolved (a symlink loop, a component that is not a folder) is not inside anything.
bool isInside(const std::filesystem::path& path, const std::filesystem::path& root);

}  // namespace pbrlab
