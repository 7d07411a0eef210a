#pragma once
// Frame: an immutable picture of the simulation after a step, made by the engine's thread and
// handed to the renderer (and the app) by value. The renderer reads only this, never a World.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace scour {

class World;

struct Frame {
  long step = 0;
  double time = 0;
  // Fluid particles.
  std::vector<Eigen::Vector3f> position;  ///< [m]
  std::vector<float> concentration;       ///< sediment C [-]
  std::vector<float> speed;               ///< |v| [m/s]
  // SPH constants the density splatting needs (the simulation's own).
  float spacing = 0, support = 0, mass = 0, rest_density = 0;
  // Terrain: nx × nz heights, row-major along x; and their change since the start.
  int nx = 0, nz = 0;
  double dx = 0, dz = 0, x0 = 0, z0 = 0;
  std::vector<float> height, change;
  /// One erosion map (engine/maps.h) when asked for: its name, its values per vertex (flow_direction:
  /// x in map, z in map2), else empty.
  std::string mapName;
  std::vector<float> map, map2;

  size_t particles() const { return position.size(); }
};

/// Copies what a Frame holds out of the world, with the erosion map called `map` (none for "";
/// std::invalid_argument for a name that is not a map).
Frame makeFrame(const World& w, const std::string& map = "");

}  // namespace scour
