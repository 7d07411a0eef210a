#pragma once
// Boundary particles on the terrain (paper §3.2), about one per Δs² of terrain whatever the
// terrain's cell (docs/model.md, "boundary particles at the fluid's spacing"):
//  - a cell as coarse as Δs or coarser (Δs / cell ≤ 2^(−1/4), where two particles per cell are
//    closer to one per Δs² than one per cell is): each of its triangles is covered by n² equal
//    sub-triangles (n = round(√area / Δs), at least 1) walked row by row like a scanline; one
//    particle sits at each sub-triangle's centroid and stands for its area, so the particles of a
//    triangle carry exactly its area (L_b² summed = triangle area);
//  - a finer terrain, with engine.boundary_sampling=spacing (the default; `triangles` samples
//    every terrain as above): the cells are grouped into blocks of b × b (b = round(Δs / cell), at most a
//    tile; clipped at the tile's edge), and one particle at the block's centre, on the terrain,
//    stands for the block's area; what it exchanges with the water is spread over the block's
//    triangles in equal parts (their projected areas are equal) when the terrain takes it
//    (TerrainAccumulator banks it whole until then), so the soil budget stays exact to rounding
//    and the terrain keeps its finer detail. A block too steep for one particle
//    (round(√(3D area) / Δs) ≥ 2) is sampled triangle by triangle as above.
//
// Sparse by design: the terrain is cut into square tiles of kTileCells × kTileCells cells, and
// particles exist only for tiles that fluid is near. The paper spent half its step on the
// boundary neighbor list over the whole terrain; here the cost follows the wet area.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "engine/heightfield.h"
#include "engine/params.h"

namespace scour {

using Vec3f = Eigen::Vector3f;

struct BoundaryParticles {
  std::vector<Vec3f> x;      ///< position on the terrain surface [m]
  std::vector<int> triangle; ///< heightfield triangle id
  std::vector<double> area;  ///< L_b², area the particle stands for [m²]
  std::vector<Eigen::Vector2f> bary;  ///< (u, w): x = c0 + u (c1 − c0) + w (c2 − c0)
  /// −1: the particle stands for part of `triangle`; else for the block of cells whose first
  /// cell (k·(nx − 1) + i) this is, `extent` cells along x (low 4 bits) and z (high 4 bits), and
  /// `triangle` is the one under its centre (which it follows).
  std::vector<int> patch;
  std::vector<uint8_t> extent;
  int cellsX = 0;  ///< the terrain's cells along x
  size_t size() const { return x.size(); }
  void clear() { x.clear(), triangle.clear(), area.clear(), bary.clear(), patch.clear(), extent.clear(); }
  /// Room for n particles in every array.
  void reserve(size_t n) {
    x.reserve(n), triangle.reserve(n), area.reserve(n), bary.reserve(n), patch.reserve(n), extent.reserve(n);
  }
  /// Appends the particles [first, last) of `from`.
  void append(const BoundaryParticles& from, size_t first, size_t last) {
    auto copy = [&](auto& to, const auto& src) { to.insert(to.end(), src.begin() + long(first), src.begin() + long(last)); };
    copy(x, from.x), copy(triangle, from.triangle), copy(area, from.area), copy(bary, from.bary);
    copy(patch, from.patch), copy(extent, from.extent);
  }
};

class BoundarySampler {
 public:
  static constexpr int kTileCells = 8;

  BoundarySampler(const Heightfield& hf, double spacing, BoundarySampling sampling);

  /// Marks the tiles within `reach` (horizontally) of any fluid particle that is within `reach`
  /// above the terrain. Returns true if the set of active tiles changed.
  bool updateActiveTiles(const Heightfield& hf, const std::vector<Vec3f>& fluid, double reach);
  /// Brings `b` to the particles of the active tiles, in tile order: a tile that `b` already
  /// holds keeps its particles (made when it became active, following the terrain since), a newly
  /// active tile is sampled from the current terrain, and a tile no longer active is dropped. `b`
  /// must be in tile order (as this leaves it); an empty one is sampled whole.
  void generate(const Heightfield& hf, BoundaryParticles& b) const;
  /// Moves the particles whose triangle has a vertex marked `epoch` in `vertexMarks` (one entry
  /// per vertex: TerrainAccumulator's marks of the vertices that moved) onto the current surface.
  static void follow(const Heightfield& hf, const std::vector<uint32_t>& vertexMarks, uint32_t epoch,
                     BoundaryParticles& b);
  /// Appends the particles of one triangle.
  static void sampleTriangle(const Heightfield& hf, int tri, double spacing, BoundaryParticles& out);
  /// Appends the particles of each triangle of the cells [i0, i1) × [k0, k1), row by row.
  static void sampleCells(const Heightfield& hf, int i0, int k0, int i1, int k1, double spacing,
                          BoundaryParticles& out);
  /// Appends the particles of the block of bx × bz cells from cell (i0, k0): one, or, when it is
  /// too steep for one, those of its halves (a single cell: those of its triangles).
  static void sampleBlock(const Heightfield& hf, int i0, int k0, int bx, int bz, double spacing,
                          BoundaryParticles& out);
  /// The block's side in cells for a terrain and Δs (engine.boundary_sampling=spacing); 0: each
  /// triangle is sampled on its own.
  static int blockCells(const Heightfield& hf, double spacing);
  int block() const { return block_; }

  const std::vector<int>& activeTiles() const { return active_; }
  /// Sets the active tiles (a restored checkpoint's); ids must be valid and ascending.
  void setActiveTiles(std::vector<int> tiles) { active_ = std::move(tiles); }
  int tileCount() const { return tilesX_ * tilesZ_; }

 private:
  double spacing_;
  int block_;
  int tilesX_, tilesZ_;
  std::vector<int> active_;
  std::vector<uint8_t> mark_;  // updateActiveTiles' marks, one copy per thread
  int tileOf(int triangle, int cellsX) const;
};

}  // namespace scour
