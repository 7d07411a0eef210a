#pragma once
// The water surface, as in the paper's §5, all on the GPU:
//   1. splat: every particle's SPH density m·W_poly6 into a regular 3D grid (fixed point, integer
//      atomics) whose bounds follow the water (its box grown by h and one cell);
//   2. occupancy: the same pass marks the 4 × 4 × 4-cell blocks that received any density;
//      compact lists them;
//   3. march: marching tetrahedra over the listed blocks only, triangles appended to a vertex
//      buffer whose counter is the vertex count of an indirect draw command.
// Nothing is read back on the interactive path; the read* functions are for tests, the bench
// and debugging. mt_reference.h holds the CPU version of step 3.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "engine/frame.h"
#include "render/gl.h"
#include "render/program.h"

namespace scour {

struct SurfaceSettings {
  double cell_over_spacing = 0.75;  ///< grid cell = this × Δs (coarsened to fit max_nodes)
  double iso = 0.5;                ///< iso level, as a fraction of ρ0
  bool occupancy = true;           ///< visit only occupied blocks
  size_t max_nodes = size_t(1) << 25;      ///< density grid nodes at most (128 MB)
  size_t max_triangles = size_t(1) << 23;  ///< vertex buffer capacity at most (800 MB)
  /// Wait for each step to finish and time it on the wall clock (bench; llvmpipe's GL timer
  /// queries read 0). Stalls the pipeline, so off by default.
  bool profile = false;
};

/// The density grid's geometry (and, read back, its values in fixed point).
struct DensityGrid {
  Eigen::Vector3f origin = Eigen::Vector3f::Zero();
  float cell = 0;
  Eigen::Vector3i nodes = Eigen::Vector3i::Zero();   ///< per axis; nodes − 1 is a multiple of 4
  Eigen::Vector3i blocks = Eigen::Vector3i::Zero();  ///< (nodes − 1) / 4
  double scale = 65536.0;           ///< fixed-point units per ρ/ρ0
  std::vector<uint32_t> value;      ///< x fastest, then y, then z
  size_t nodeCount() const { return size_t(nodes.x()) * nodes.y() * nodes.z(); }
  size_t blockCount() const { return size_t(blocks.x()) * blocks.y() * blocks.z(); }
};

struct SurfaceVertex {
  Eigen::Vector3f position, normal;
};
using SurfaceTriangle = std::array<SurfaceVertex, 3>;

struct SurfaceStats {
  long triangles = 0, dropped = 0;  ///< appended; lost to a full buffer
  long blocks = 0, occupied = 0;    ///< blocks in the grid; occupied (visited) ones
};

class WaterSurface {
 public:
  explicit WaterSurface(SurfaceSettings s = {});
  ~WaterSurface();
  WaterSurface(const WaterSurface&) = delete;
  WaterSurface& operator=(const WaterSurface&) = delete;

  /// Splats, marks and extracts the surface of the frame's particles.
  void update(const Frame& f);
  /// After an update that lost triangles to a full vertex buffer: grows the buffer to fit them
  /// and returns true (update again). Reads back a few bytes; for headless pictures and tests.
  bool growIfOverflowed();
  /// Runs the march over the last update's grid in count-only mode: finds the iso-cubes (cells
  /// the surface crosses) without making triangles. Returns their number and the wall time.
  long countIsoCubes(double* seconds);

  const SurfaceSettings& settings() const { return s_; }
  void setSettings(const SurfaceSettings& s) { s_ = s; }
  const DensityGrid& grid() const { return grid_; }  ///< geometry of the last update
  GLuint vertexBuffer() const { return vertices_; }  ///< vec4 position, vec4 normal per vertex
  GLuint drawBuffer() const { return draw_; }        ///< DrawArraysIndirectCommand
  GLuint particleBuffer() const { return particles_; }  ///< vec4 per particle of the last update
  GLuint densityBuffer() const { return density_; }     ///< the grid's values, fixed point
  /// Wall-clock seconds of each step of the last update, with `profile` on (else 0).
  struct Timings {
    double splat = 0, occupancy = 0, march = 0;
  };
  Timings readTimings() const;

  DensityGrid readDensity() const;
  std::vector<SurfaceTriangle> readTriangles() const;
  SurfaceStats readStats() const;

 private:
  void layout(const Frame& f);
  void reserve(size_t particles);
  void march(bool countOnly = false);

  SurfaceSettings s_;
  DensityGrid grid_;
  Program splat_, compact_, finish_, march_;
  GLuint particles_ = 0, density_ = 0, occupancy_ = 0, list_ = 0, vertices_ = 0, draw_ = 0;
  size_t particleCap_ = 0, nodeCap_ = 0, blockCap_ = 0, listCap_ = 0, vertexCap_ = 0;
  double wall_[3] = {0, 0, 0};  ///< seconds of the last update's steps, when profiling
};

}  // namespace scour
