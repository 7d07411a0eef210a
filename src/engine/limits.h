#pragma once
// What one run may ask of the machine. Everything that allocates or loops in proportion to a
// number the user gives (Δs, a block of water, a terrain grid, a source's disk and rate, a rain's
// rectangle and intensity, the brush) is estimated against these limits before it starts, and
// refused with the numbers (docs/scene-format.md, "Limits"). The scene reader, buildScene and
// the World's live edits all go through the functions here, so the three cannot disagree.

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/params.h"
#include "engine/sources.h"

namespace scour {

struct Limits {
  /// Memory a run may hold: particles and terrain together [bytes].
  static constexpr double kMaxBytes = 16e9;
  /// Upper estimate of what one fluid particle holds (state arrays, neighbor lists, grid) [bytes].
  static constexpr double kBytesPerParticle = 500;
  /// Upper estimate of what one terrain vertex holds (heights, areas, exchange, tiles) [bytes].
  static constexpr double kBytesPerVertex = 120;
  /// Terrain grid vertices.
  static constexpr double kMaxTerrainVertices = 4e7;
  /// Particles one step may place (all sources and rain together): bounds a step's work.
  static constexpr double kMaxPlacedPerStep = 2e5;
};

/// Particles a terrain of `vertices` leaves room for within Limits::kMaxBytes.
inline double particleCapacity(double vertices) {
  return std::max(0.0, (Limits::kMaxBytes - vertices * Limits::kBytesPerVertex) / Limits::kBytesPerParticle);
}

/// Bytes a run of this many particles and terrain vertices holds (the estimate the limit uses).
inline double footprintBytes(double particles, double vertices) {
  return particles * Limits::kBytesPerParticle + vertices * Limits::kBytesPerVertex;
}

/// The longest step a run of these parameters takes [s]: the fixed step, or the adaptive cap.
inline double longestStep(const SimParams& p) { return p.fixed_dt > 0 ? p.fixed_dt : p.max_dt; }

/// An upper bound on a source's slots (lattice points of spacing Δs in its disk), computed
/// without making them.
inline double sourceSlotBound(double radius, double spacing) {
  const double n = 2 * std::ceil(radius / spacing) + 1;
  return n * n;
}

/// An upper bound on the particles a source places in one step of at most `dt`: its volume
/// Q·Δt in particles, plus one layer of slots for the layer that may come due.
inline double sourcePlacedPerStep(const Source& s, double spacing, double slots, double dt) {
  return s.rate * dt / (spacing * spacing * spacing) + slots;
}

/// The part of a rain's rectangle over the terrain [x0, x1] × [z0, z1] [m²].
inline double rainArea(const Rain& r, double x0, double x1, double z0, double z1) {
  const double w = std::min(r.hi_x, x1) - std::max(r.lo_x, x0);
  const double d = std::min(r.hi_z, z1) - std::max(r.lo_z, z0);
  return w > 0 && d > 0 ? w * d : 0.0;
}

/// Drops a rain over `area` [m²] places in one step of at most `dt`.
inline double rainPlacedPerStep(const Rain& r, double area, double spacing, double dt) {
  return r.intensity_mm_h / 3.6e6 * area * dt / (spacing * spacing * spacing) + 1;
}

/// Checks a source against the limits (without making its slots): "" or what is wrong, naming
/// `at` (e.g. "sources[2]"): its slots and the particles it places per step, and its exit speed
/// Q / (slots·Δs²), which must stay below the sound speed: the weakly compressible fluid cannot
/// carry a faster jet, and a layer would be due every step.
std::string checkSourceWork(const Source& s, const SimParams& p, const std::string& at);

/// Checks a rain over `area` m² of terrain (rainArea): "" or, naming `at`, that it places more
/// drops per step than the limit. (A rectangle that misses the terrain is the caller's to refuse.)
std::string checkRainWork(const Rain& r, double area, const SimParams& p, const std::string& at);

/// The exit speed alone, for `slots` slots.
std::string checkSourceSpeed(const Source& s, const SimParams& p, double slots, const std::string& at);

}  // namespace scour
