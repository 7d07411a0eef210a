#pragma once
// Boundary particles on the terrain (paper §3.2). Each heightfield triangle is covered by n² equal
// sub-triangles (n = round(√area / Δs), at least 1) walked row by row like a scanline; one boundary particle
// sits at each sub-triangle's centroid and stands for its area, so the particles of a triangle
// carry exactly its area (L_b² summed = triangle area), which the erosion budget relies on.
//
// Sparse by design: the terrain is cut into square tiles of kTileCells × kTileCells cells, and
// particles exist only for tiles that fluid is near. The paper spent half its step on the
// boundary neighbor list over the whole terrain; here the cost follows the wet area.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "engine/heightfield.h"

namespace scour {

using Vec3f = Eigen::Vector3f;

struct BoundaryParticles {
  std::vector<Vec3f> x;      ///< position on the terrain surface [m]
  std::vector<int> triangle; ///< heightfield triangle id
  std::vector<double> area;  ///< L_b², area the particle stands for [m²]
  std::vector<Eigen::Vector2f> bary;  ///< (u, w): x = c0 + u (c1 − c0) + w (c2 − c0)
  size_t size() const { return x.size(); }
};

class BoundarySampler {
 public:
  static constexpr int kTileCells = 8;

  explicit BoundarySampler(const Heightfield& hf, double spacing);

  /// Marks the tiles within `reach` (horizontally) of any fluid particle that is within `reach`
  /// above the terrain. Returns true if the set of active tiles changed.
  bool updateActiveTiles(const Heightfield& hf, const std::vector<Vec3f>& fluid, double reach);
  /// Regenerates the particles of all active tiles, in tile order.
  void generate(const Heightfield& hf, BoundaryParticles& out) const;
  /// Moves the particles of the given triangles (sorted ids) onto the current surface.
  static void follow(const Heightfield& hf, const std::vector<int>& triangles, BoundaryParticles& b);
  /// Appends the particles of one triangle.
  static void sampleTriangle(const Heightfield& hf, int tri, double spacing, BoundaryParticles& out);

  const std::vector<int>& activeTiles() const { return active_; }
  /// Sets the active tiles (a restored checkpoint's); ids must be valid and ascending.
  void setActiveTiles(std::vector<int> tiles) { active_ = std::move(tiles); }
  int tileCount() const { return tilesX_ * tilesZ_; }

 private:
  double spacing_;
  int tilesX_, tilesZ_;
  std::vector<int> active_;
  std::vector<uint8_t> mark_;
};

}  // namespace scour
