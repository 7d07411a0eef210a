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
#include <limits>
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
