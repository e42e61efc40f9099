// The precomputed maps' disk cache: the file format of a cached cube or LUT (on cache_file.h).
// What the cache keys hold is IblPrecompute::mapsKey and lutKey (ibl/map_cache.cpp).
#pragma once

#include <filesystem>
#include <vector>

#include "assets/image_io.h"

namespace pbrlab {

// Names what the CPU code computes (cube resampling, irradiance bins) in the cache keys: bump it
// when ibl/cpu_maps.cpp changes what it writes.
inline constexpr const char* kCpuMapsVersion = "cpu-maps-2";

// levels x faces RGBA32F images (faces: 6, or 1 for the LUT), as read back. False when the
// file could not be written or read whole (a cache miss, never an error).
bool writeMaps(const std::filesystem::path& file, const std::vector<std::vector<Image>>& levels);
bool readMaps(const std::filesystem::path& file, std::vector<std::vector<Image>>& levels);
// `count` levels of six faces, level l of size >> l.
bool sizesAre(const std::vector<std::vector<Image>>& levels, int size, int count);
// writeMaps, with a journal line when it fails (a cache that cannot be written only costs time).
void storeQuietly(const std::filesystem::path& file, const std::vector<std::vector<Image>>& levels);

}  // namespace pbrlab
