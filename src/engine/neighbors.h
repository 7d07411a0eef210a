#pragma once
// Uniform-grid neighbor search. Cells are cubes of edge h over the fluid's bounding box; a counting
// sort puts particle indices in cell order, and each fluid particle's neighbors within h (fluid and
// boundary particles alike) are gathered once per step into lists that every pass shares.
//
// Determinism: a particle's list is built by one thread, scanning the 27 cells in a fixed order and
// each cell in ascending particle order, so the lists are the same at any thread count. The lists
// are stored in one chunk per thread (no copy); a particle's list is a pointer and a count.
//
// kd-tree (engine.neighbor_search = kd_tree, the paper's choice): a nanoflann tree over the fluid
// (or the boundary) particles, rebuilt every step. Each radius query is widened slightly and then
// filtered with the grid's own test, |x_i − y_j|² < h² in float, so both searches find the same
// neighbor sets; a kd-tree list is sorted by ascending index (deterministic at any thread count,
// but a different order from the grid's cell order, so sums over it round differently).
//
// Z-order: zOrder() returns the permutation that sorts particles along the Morton curve of their
// cell coordinates; World applies it every few steps so that neighbors are near in memory.

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/params.h"

namespace scour {

using Vec3f = Eigen::Vector3f;

class Grid {
 public:
  /// Bins points into cells of edge `cell` over their bounding box (expanded by one cell). Should
  /// that take more than max(kMaxCells, 512 per point) cells (points flung far apart), the
  /// cells are widened until it does not; a point that is not finite goes into an edge cell.
  void build(const std::vector<Vec3f>& x, float cell);
  static constexpr size_t kMaxCells = size_t(1) << 25;
  /// Bins a second point set (boundary particles) into the same cells; points outside are dropped.
  void binOther(const std::vector<Vec3f>& y, std::vector<uint32_t>& start,
                std::vector<uint32_t>& sorted) const;

  float cell() const { return cell_; }
  const Eigen::Vector3i& dims() const { return dims_; }
  const Vec3f& origin() const { return origin_; }
  Eigen::Vector3i cellOf(const Vec3f& p) const;
  int linear(int cx, int cy, int cz) const { return cx + dims_.x() * (cy + dims_.y() * cz); }
  bool inside(int cx, int cy, int cz) const {
    return cx >= 0 && cy >= 0 && cz >= 0 && cx < dims_.x() && cy < dims_.y() && cz < dims_.z();
  }

  const std::vector<uint32_t>& start() const { return start_; }
  const std::vector<uint32_t>& sorted() const { return sorted_; }
  /// How many points the last build indexed (indices 0 … count − 1).
  size_t particleCount() const { return sorted_.size(); }

  /// Calls f(j) for every indexed point j in the 27 cells around p (no distance test). Cells
  /// cx−1..cx+1 of one row are consecutive in the linear order, so each of the 9 rows is one
  /// contiguous range of the sorted array.
  template <class F>
  void forEachCandidate(const Vec3f& p, const std::vector<uint32_t>& start,
                        const std::vector<uint32_t>& sorted, F&& f) const {
    forEachCandidateRange(p, start, [&](uint32_t b, uint32_t e) {
      for (uint32_t k = b; k < e; ++k) f(sorted[k]);
    });
  }
  /// The same candidates as ranges [b, e) of the sorted array, a non-empty one per row of
  /// cells, in the same order.
  template <class F>
  void forEachCandidateRange(const Vec3f& p, const std::vector<uint32_t>& start, F&& f) const {
    Eigen::Vector3i c = cellOf(p);
    const int xa = std::max(c.x() - 1, 0), xb = std::min(c.x() + 1, dims_.x() - 1);
    if (xa > xb) return;
    for (int cz = c.z() - 1; cz <= c.z() + 1; ++cz) {
      if (cz < 0 || cz >= dims_.z()) continue;
      for (int cy = c.y() - 1; cy <= c.y() + 1; ++cy) {
        if (cy < 0 || cy >= dims_.y()) continue;
        const uint32_t b = start[linear(xa, cy, cz)], e = start[linear(xb, cy, cz) + 1];
        if (b < e) f(b, e);
      }
    }
  }

  /// Morton-order permutation of the points last passed to build().
  std::vector<uint32_t> zOrder(const std::vector<Vec3f>& x) const;

  size_t bytes() const { return (start_.capacity() + sorted_.capacity()) * sizeof(uint32_t); }

 private:
  /// Counting sort of point indices by cell (index −1: not binned) into (start, sorted).
  static void countingSort(const std::vector<int64_t>& cellIdx, size_t cells,
                           std::vector<uint32_t>& start, std::vector<uint32_t>& sorted);

  float cell_ = 1.0f;
  Vec3f origin_ = Vec3f::Zero();
  Eigen::Vector3i dims_ = Eigen::Vector3i::Ones();
  std::vector<uint32_t> start_, sorted_;
};

/// A kd-tree over a point set (nanoflann, kept out of this header). It refers to the vector it
/// was built on, which must outlive it and stay unchanged while it is queried.
class KdTree {
 public:
  KdTree();
  ~KdTree();
  KdTree(KdTree&&) noexcept;
  KdTree& operator=(KdTree&&) noexcept;

  /// Indexes the points y (rebuilds from scratch).
  void build(const std::vector<Vec3f>& y);
  /// Appends to `out` the indexed points j with |p − y_j| ≤ r (a superset of those strictly
  /// within r: the caller filters), in no particular order. Thread-safe.
  void candidates(const Vec3f& p, float r, std::vector<uint32_t>& out) const;
  /// The points last passed to build() (nullptr before the first).
  const std::vector<Vec3f>* points() const;
  size_t bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Per-particle neighbor lists, stored in per-thread chunks.
class NeighborLists {
 public:
  /// Neighbors j ≠ i of each x[i] among `x` (self = true) or among the points binned in
  /// (start, sorted) with positions y, within radius r. `inCellOrder` is scratch: y's x, y and z
  /// coordinates, each in the order of `sorted` (three blocks of sorted.size()), so the candidates
  /// of a row of cells are read one after the other, four at a time.
  void build(const Grid& grid, const std::vector<Vec3f>& x, const std::vector<Vec3f>& y,
             const std::vector<uint32_t>& start, const std::vector<uint32_t>& sorted, float r,
             bool self, std::vector<float>& inCellOrder);
  void build(const Grid& grid, const std::vector<Vec3f>& x, const std::vector<Vec3f>& y,
             const std::vector<uint32_t>& start, const std::vector<uint32_t>& sorted, float r,
             bool self) {
    std::vector<float> scratch;
    build(grid, x, y, start, sorted, r, self, scratch);
  }
  /// The same sets from a kd-tree over y (= tree.points()), each list in ascending index.
  void build(const KdTree& tree, const std::vector<Vec3f>& x, float r, bool self);

  size_t size() const { return count_.size(); }
  uint32_t count(size_t i) const { return count_[i]; }
  const uint32_t* begin(size_t i) const { return first_[i]; }
  size_t totalPairs() const;
  size_t bytes() const;

 private:
  /// Runs gather(i, chunk, end) for i = order[k] (or k, with no order), each thread a block of
  /// ascending k; gather writes i's neighbors into the chunk from index `end` on (growing it if it
  /// must: its size is a high-water mark, not the lists' end) and returns their new end. The
  /// order only places the lists in the chunks: each list is the same in any order.
  template <class Gather>
  void fill(size_t n, const uint32_t* order, Gather&& gather);

  std::vector<std::vector<uint32_t>> chunks_;
  std::vector<const uint32_t*> first_;
  std::vector<uint32_t> count_;
};

/// Calls f(j, xij, r) for each neighbor j of particle i, with xij = x[i] − y[j] and r = |xij|.
template <class F>
inline void forEachNeighbor(const NeighborLists& n, const std::vector<Vec3f>& x,
                            const std::vector<Vec3f>& y, size_t i, F&& f) {
  const uint32_t* js = n.begin(i);
  const uint32_t c = n.count(i);
  const Vec3f xi = x[i];
  for (uint32_t k = 0; k < c; ++k) {
    const uint32_t j = js[k];
    const Vec3f xij = xi - y[j];
    f(j, xij, xij.norm());
  }
}

/// The World's neighbor search: the uniform grid (or the paper's kd-trees, as
/// engine.neighbor_search says) and the fluid–fluid and fluid–boundary lists every pass shares.
/// Rebuilt every step from the particles; nothing of it is saved with a world state.
class Neighborhood {
 public:
  /// The fluid–fluid lists of the particles at x, within h.
  void buildFluid(const std::vector<Vec3f>& x, float h, NeighborSearch method);
  /// The fluid–boundary lists, after buildFluid on the same fluid.
  void buildBoundary(const std::vector<Vec3f>& fluid, const std::vector<Vec3f>& boundary, float h,
                     NeighborSearch method);
  /// The grid over the particles of the last search (placement looks up its cells; the Z-order
  /// reorder sorts by it). In kd-tree mode it is built here, on demand, over x.
  const Grid& placementGrid(const std::vector<Vec3f>& x, float h);
  /// The grid built anew over x (the Z-order reorder).
  const Grid& rebuildGrid(const std::vector<Vec3f>& x, float h);

  const NeighborLists& fluid() const { return fluid_; }
  const NeighborLists& boundary() const { return boundary_; }
  size_t bytes() const;

 private:
  Grid grid_;
  /// kd-tree mode: the grid is built on demand for placement and the Z-order, not by the search.
  bool gridStale_ = false;
  KdTree fluidTree_, boundaryTree_;
  NeighborLists fluid_, boundary_;
  std::vector<uint32_t> boundaryStart_, boundarySorted_;  ///< the boundary particles binned
  std::vector<float> inCellOrder_;  ///< the build's scratch (NeighborLists::build)
};

/// A fixed partition of [0, n) into `parts` ranges, independent of the thread count.
inline size_t blockBegin(size_t n, size_t parts, size_t b) { return n * b / parts; }

}  // namespace scour
