#pragma once
// Output files. Every writer goes through writeAtomically: the bytes go to a temporary file next
// to the target, which is renamed over it only when complete, so an interrupted run never leaves
// half a file.

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

#include "engine/fluid.h"
#include "engine/heightfield.h"

#include <utility>
#include <vector>

namespace scour {

/// Writes via `fill` into "<path>.tmp-<pid>" and renames it to `path`. Throws std::runtime_error
/// naming the file if anything fails (the temporary is removed).
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(std::ostream&)>& fill);

/// Binary little-endian PLY of the fluid particles: x y z vx vy vz c (float; c the sediment
/// concentration C), with the simulated time in a `comment time_s` header line. y is up.
void writeParticlesPly(const std::filesystem::path& path, const Fluid& f, double particleVolume,
                       double time);

/// A heightfield image: row k holds z = z0 + k·dz, column i holds x = x0 + i·dx.
/// 16-bit greyscale PNG, v = round((h − lo) / (hi − lo) · 65535). Returns {lo, hi}.
std::pair<double, double> writeHeightPng16(const std::filesystem::path& path, const Heightfield& hf);

/// A map on a grid as a 16-bit greyscale PNG, v = round(value / top · 65535) with top the largest
/// value (all 0 when it is 0; negative values are written as 0). Returns top.
double writeMapPng16(const std::filesystem::path& path, int nx, int nz, const std::vector<double>& values);

/// A direction map as a 16-bit RGB PNG, like a normal map: R = (x + 1) / 2, G = (z + 1) / 2 of
/// unit components in [−1, 1], B = 1 where there is a direction and 0 where there is none.
void writeDirectionPng16(const std::filesystem::path& path, int nx, int nz, const std::vector<double>& x,
                         const std::vector<double>& z);

/// Unreal Engine's 16-bit raw heightmap: uint16 little-endian, row-major as the PNG, v =
/// round((h − lo) / (hi − lo) · 65535). Returns {lo, hi}.
std::pair<double, double> writeHeightR16(const std::filesystem::path& path, const Heightfield& hf);

/// A grid of values as a float32 OpenEXR image with one channel, Y (ZIP compression), row k of the
/// image the grid's row k. The values as float, unscaled: heights in metres, a map in its unit.
void writeGridExr(const std::filesystem::path& path, int nx, int nz, const std::vector<double>& values);
/// The same with named channels (flow_direction: R and G), each nx × nz values.
void writeGridExr(const std::filesystem::path& path, int nx, int nz,
                  const std::vector<std::pair<std::string, const std::vector<double>*>>& channels);

/// Raw float32, little-endian, row-major (rows of nx values, nz rows; same order as the PNG).
void writeHeightRaw(const std::filesystem::path& path, const Heightfield& hf);

/// The terrain as a Wavefront OBJ mesh: one vertex per grid point (x, h, z) with its normal (the
/// area-weighted mean of the adjacent triangles'), two triangles per cell as in the engine,
/// counter-clockwise seen from above.
void writeTerrainObj(const std::filesystem::path& path, const Heightfield& hf);

/// False-colour map of the height change since the start, like the paper's Figures 1 and 8:
/// white unchanged, red erosion, blue deposition, full colour at |Δh| = scale (symmetric).
/// 8-bit RGB PNG; returns the scale used [m] (the largest |Δh|, or 0 if nothing moved).
double writeErosionPng(const std::filesystem::path& path, const Heightfield& hf,
                       const std::vector<double>& change);

}  // namespace scour
