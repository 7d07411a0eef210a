#pragma once
// Frame: an immutable picture of the simulation after a step, made by the engine's thread and
// handed to the renderer (and the app) by value. The renderer reads only this, never a World.

#include <Eigen/Core>
#include <cstdint>
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

  size_t particles() const { return position.size(); }
};

/// Copies what a Frame holds out of the world.
Frame makeFrame(const World& w);

}  // namespace scour
