#pragma once
// Water sources (emitters) and sinks.
//
// A source is a disk (centre, radius, unit direction) with a volume flow rate Q. Its slots are a
// square lattice of spacing Δs inside the disk; every time the previously emitted layer has
// travelled Δs at the exit speed u = Q / (slots · Δs²), a new layer is placed, so the emitted
// volume is exactly Q·t (in whole layers) and new particles never sit on each other. A slot that
// an existing particle still occupies (closer than Δs/2) is skipped and counted as blocked.
//
// A sink is an axis-aligned box; particles that enter it are removed and counted.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace scour {

struct Source {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< [m]
  double radius = 0.1;                                ///< [m]
  Eigen::Vector3d direction{0, -1, 0};                ///< unit
  double rate = 0.001;                                ///< Q, volume flow [m³/s]
  double start = 0.0;                                 ///< [s]
  double stop = std::numeric_limits<double>::infinity();  ///< [s]
};

struct Sink {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();  ///< box [m]
  bool contains(const Eigen::Vector3f& p) const {
    return p.x() >= lo.x() && p.y() >= lo.y() && p.z() >= lo.z() && p.x() <= hi.x() &&
           p.y() <= hi.y() && p.z() <= hi.z();
  }
};

/// Rain over the rectangle [lo_x, hi_x] × [lo_z, hi_z]: `intensity_mm_h` millimetres of water per
/// hour fall on it (kept in the unit scene files use, so a scene round-trips exactly). Each particle's volume Δs³ that has accumulated becomes one drop at
/// a pseudo-random point of the rectangle (counter-based, so a run is reproducible and a
/// checkpoint needs only the counter), `drop_height` above the terrain, falling at `drop_speed`.
/// A drop whose place is still occupied is skipped and counted as blocked.
struct Rain {
  double lo_x = 0, lo_z = 0, hi_x = 0, hi_z = 0;  ///< [m]
  double intensity_mm_h = 36.0;                     ///< [mm/h]
  double drop_height = 0.1;                         ///< [m]
  double drop_speed = 1.0;                          ///< [m/s]
  double start = 0.0;                               ///< [s]
  double stop = std::numeric_limits<double>::infinity();  ///< [s]
  uint64_t seed = 1;
};

/// Progress of one rain: volume not yet turned into drops, drops drawn so far.
struct RainState {
  Rain rain;
  double pending = 0.0;  ///< [m³]
  uint64_t drawn = 0;
  long emitted = 0, blocked = 0;
  /// The k-th point of the rain's sequence, as two numbers in [0, 1).
  static std::pair<double, double> point(uint64_t seed, uint64_t k);
};

/// The slots of a source's disk: the points (u, w) of the square lattice of spacing Δs within
/// `radius` of its centre, in the disk plane; at least the centre.
std::vector<Eigen::Vector2d> diskLattice(double radius, double spacing);

/// Emission state of one source.
struct Emitter {
  Source src;
  std::vector<Eigen::Vector3d> slots;  ///< offsets from the centre, in the disk plane
  double speed = 0.0;                  ///< u [m/s]
  double travelled = 0.0;              ///< distance the last layer has moved [m]
  long emitted = 0, blocked = 0;

  Emitter(const Source& s, double spacing);
};

}  // namespace scour
