#pragma once
// The size checks every heightmap reader makes before it allocates (terrain.cpp's PNG, EXR and
// raw readers, geodata.cpp's GDAL reader), with the same messages.

#include <string>

#include "scene/presets.h"

namespace scour {

/// Most pixels a heightmap may have: 134 M, 1 GB of doubles.
constexpr long long kMaxHeightmapPixels = 1LL << 27;
/// Deflate packs at most about 1,030 bytes into one (PNG rows add a filter byte each): a header
/// claiming more pixels per byte of its file is not a heightmap, and reading it would fill a
/// buffer of the claimed size.
constexpr double kMaxHeightmapPixelsPerByte = 1100;

/// TerrainError when a w × h `picture` ("image", "raster") read from `bytes` bytes of `file` is
/// smaller than 2 × 2, larger than kMaxHeightmapPixels, or more than `holder` ("a PNG", "an EXR",
/// "the file") can hold.
inline void checkHeightmapSize(const std::string& file, long long w, long long h, double bytes,
                               const std::string& picture, const std::string& holder) {
  const std::string size = std::to_string(w) + " × " + std::to_string(h);
  if (w < 2 || h < 2) throw TerrainError(file + ": a " + size + " " + picture + ": a heightmap needs at least 2 × 2 pixels");
  if (w * h > kMaxHeightmapPixels) throw TerrainError(file + ": " + size + " pixels is more than this build reads");
  if (1.0 * w * h > kMaxHeightmapPixelsPerByte * bytes)
    throw TerrainError(file + ": its header claims " + size + " pixels in " + std::to_string((long long)bytes) +
                       " bytes, more than " + holder + " can hold");
}

}  // namespace scour
