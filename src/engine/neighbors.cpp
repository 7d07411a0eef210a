#include "engine/neighbors.h"

#include <omp.h>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>

#include <nanoflann.hpp>

#include "engine/fluid.h"
#include "engine/parallel.h"

namespace scour {

void Fluid::gather(const std::vector<uint32_t>& order) {
  forEachArray([&](const char*, auto& array) {
    std::remove_reference_t<decltype(array)> out(order.size());
    for (size_t k = 0; k < order.size(); ++k) out[k] = array[order[k]];
    array.swap(out);
  });
}

Eigen::Vector3i Grid::cellOf(const Vec3f& p) const {
  // Far outside (or not a number, which compares false) clamps to just outside the grid: the
  // clamp never brings two points closer in cells than they are, so nothing within reach is lost.
  auto axis = [](float q) { return q >= -1.0f ? (q < 2e9f ? int(std::floor(q)) : 2000000000) : -1; };
  const Vec3f q = (p - origin_) / cell_;
  return {axis(q.x()), axis(q.y()), axis(q.z())};
}

void Grid::build(const std::vector<Vec3f>& x, float cell) {
  const size_t n = x.size();
  Vec3f lo = Vec3f::Constant(std::numeric_limits<float>::max()), hi = -lo;
  if (n == 0) lo = hi = Vec3f::Zero();
  // min/max are exact, so the result does not depend on how the threads split the work.
#pragma omp parallel if (n >= kParallelFrom)
  {
    Vec3f tlo = Vec3f::Constant(std::numeric_limits<float>::max()), thi = -tlo;
#pragma omp for schedule(static) nowait
    for (size_t i = 0; i < n; ++i) {
      if (!x[i].allFinite()) continue;  // binned into an edge cell below
      tlo = tlo.cwiseMin(x[i]);
      thi = thi.cwiseMax(x[i]);
    }
#pragma omp critical
    {
      lo = lo.cwiseMin(tlo);
      hi = hi.cwiseMax(thi);
    }
  }
  if (!(lo.array() <= hi.array()).all()) lo = hi = Vec3f::Zero();  // no finite point
  // A blow-up can throw a few particles kilometres away. The grid stays within a memory bound by
  // widening its cells (cells at least `cell` wide still hold every point within `cell` in the
  // 27 around); a healthy run is far below the bound and keeps cells of exactly `cell`.
  const double maxCells = std::max(double(kMaxCells), 512.0 * double(n));
  const Eigen::Vector3d span = (hi - lo).cast<double>();
  double edge = cell;
  auto cellsAt = [&](double e) { return (span.x() / e + 4) * (span.y() / e + 4) * (span.z() / e + 4); };
  while (cellsAt(edge) > maxCells) edge *= 2;
  cell_ = float(edge);
  origin_ = lo - Vec3f::Constant(cell_);
  Vec3f ext = (hi - origin_) / cell_;
  dims_ = {int(ext.x()) + 2, int(ext.y()) + 2, int(ext.z()) + 2};
  const size_t cells = size_t(dims_.x()) * dims_.y() * dims_.z();
  std::vector<int64_t> cellIdx(n);
#pragma omp parallel for schedule(static) if (n >= kParallelFrom)
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3i c = cellOf(x[i]).cwiseMax(0).cwiseMin(dims_ - Eigen::Vector3i::Ones());
    cellIdx[i] = linear(c.x(), c.y(), c.z());
  }
  countingSort(cellIdx, cells, start_, sorted_);
}

void Grid::countingSort(const std::vector<int64_t>& cellIdx, size_t cells,
                        std::vector<uint32_t>& start, std::vector<uint32_t>& sorted) {
  // Placing in ascending index keeps each cell's list in point order; index −1 is left out.
  start.assign(cells + 1, 0);
  for (int64_t c : cellIdx)
    if (c >= 0) ++start[size_t(c) + 1];
  for (size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  sorted.resize(start[cells]);
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (size_t i = 0; i < cellIdx.size(); ++i)
    if (cellIdx[i] >= 0) sorted[fill[size_t(cellIdx[i])]++] = uint32_t(i);
}

void Grid::binOther(const std::vector<Vec3f>& y, std::vector<uint32_t>& start,
                    std::vector<uint32_t>& sorted) const {
  const size_t cells = size_t(dims_.x()) * dims_.y() * dims_.z();
  std::vector<int64_t> cellIdx(y.size(), -1);
#pragma omp parallel for schedule(static) if (y.size() >= kParallelFrom)
  for (size_t i = 0; i < y.size(); ++i) {
    Eigen::Vector3i c = cellOf(y[i]);
    if (inside(c.x(), c.y(), c.z())) cellIdx[i] = linear(c.x(), c.y(), c.z());
  }
  countingSort(cellIdx, cells, start, sorted);
}

namespace {
// Interleaves the low 21 bits of v with two zero bits between each.
uint64_t spread3(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}
}  // namespace

std::vector<uint32_t> Grid::zOrder(const std::vector<Vec3f>& x) const {
  const size_t n = x.size();
  std::vector<std::pair<uint64_t, uint32_t>> keys(n);
#pragma omp parallel for schedule(static) if (n >= kParallelFrom)
  for (size_t i = 0; i < n; ++i) {
    Eigen::Vector3i c = cellOf(x[i]);
    keys[i] = {spread3(uint64_t(c.x())) | spread3(uint64_t(c.y())) << 1 |
                   spread3(uint64_t(c.z())) << 2,
               uint32_t(i)};
  }
  std::sort(keys.begin(), keys.end());  // (key, index) pairs: a total order, so deterministic
  std::vector<uint32_t> order(n);
  for (size_t k = 0; k < n; ++k) order[k] = keys[k].second;
  return order;
}

template <class Gather>
void NeighborLists::fill(size_t n, const uint32_t* order, Gather&& gather) {
  resizeForParticles(first_, n);
  resizeForParticles(count_, n);
#pragma omp parallel
  {
    const int threads = omp_get_num_threads(), t = omp_get_thread_num();
#pragma omp single
    chunks_.resize(std::max<size_t>(chunks_.size(), size_t(threads)));
    // implicit barrier after single
    std::vector<uint32_t>& chunk = chunks_[t];
    // The chunk's size is its high-water mark: gather writes from `end` on, grows it when it must
    // (never zero-filling what it keeps), and returns the list's new end.
    size_t end = 0;
    const size_t b = blockBegin(n, threads, t), e = blockBegin(n, threads, t + 1);
    for (size_t k = b; k < e; ++k) {
      const size_t i = order ? order[k] : k;
      const size_t after = gather(i, chunk, end);
      count_[i] = uint32_t(after - end);
      end = after;
    }
    // Lists that shrank by more than an eighth (the water spread out since the high-water mark)
    // give the rest back, keeping a sixteenth for the next builds to grow into.
    if (chunk.size() > end + end / 8 + 4096) chunk.resize(end + end / 16), chunk.shrink_to_fit();
    const uint32_t* p = chunk.data();
    for (size_t k = b; k < e; ++k) {
      const size_t i = order ? order[k] : k;
      first_[i] = p;
      p += count_[i];
    }
  }
}

void NeighborLists::build(const Grid& grid, const std::vector<Vec3f>& x,
                          const std::vector<Vec3f>& y, const std::vector<uint32_t>& start,
                          const std::vector<uint32_t>& sorted, float r, bool self,
                          std::vector<float>& inCellOrder) {
  const float r2 = r * r;
  const size_t m = sorted.size();
  resizeForParticles(inCellOrder, 3 * m);
  float* const X = inCellOrder.data();
  float* const Y = X + m;
  float* const Z = Y + m;
#pragma omp parallel for schedule(static) if (m >= kParallelFrom)
  for (size_t k = 0; k < m; ++k) {
    const Vec3f& p = y[sorted[k]];
    X[k] = p.x(), Y[k] = p.y(), Z[k] = p.z();
  }
  // Particles in Z-order come in runs of one cell: the rows of cells around a cell are found once
  // for the run (each thread its own).
  struct alignas(64) Rows {  // a cache line or more each: no thread writes into another's line
    Eigen::Vector3i cell{-2, -2, -2};
    int count = 0;
    uint32_t begin[9], end[9];
    uint32_t candidates = 0;
  };
  std::vector<Rows> rowsOf(static_cast<size_t>(omp_get_max_threads()));
  // Particles taken cell by cell when the grid holds x (its sorted points are a permutation of
  // x's indices), so each thread finds a cell's rows once for all its particles (in index order
  // about a third of the particles begin a new run of cells: the Z-order is only redone every
  // few steps); any other x is taken in index order. The rows are those of each particle's own
  // cell either way, so the lists are the same.
  const uint32_t* order = grid.sorted().size() == x.size() ? grid.sorted().data() : nullptr;
  fill(x.size(), order, [&](size_t i, std::vector<uint32_t>& chunk, size_t at) {
    const Vec3f xi = x[i];
    Rows& rows = rowsOf[size_t(omp_get_thread_num())];
    const Eigen::Vector3i c = grid.cellOf(xi);
    if (c != rows.cell) {
      rows.cell = c, rows.count = 0, rows.candidates = 0;
      grid.forEachCandidateRange(xi, start, [&](uint32_t b, uint32_t e) {
        rows.begin[rows.count] = b, rows.end[rows.count++] = e;
        rows.candidates += e - b;
      });
    }
    // Without a branch: every candidate is written, and the end moves past it when it is a
    // neighbor (a branch on it mispredicted too often).
    // A chunk too short grows as reserveWithSlack does; its size is the high-water mark the next
    // builds reuse.
    if (chunk.size() < at + rows.candidates) reserveWithSlack(chunk, at + rows.candidates), chunk.resize(chunk.capacity());
    uint32_t* const base = chunk.data();
    uint32_t* out = base + at;
    // |x_i − y_k|² as Eigen's squaredNorm, dx² + (dy² + dz²): the same pairs as Vec3f's.
    auto near = [&](uint32_t k) {
      const float dx = xi.x() - X[k], dy = xi.y() - Y[k], dz = xi.z() - Z[k];
      return dx * dx + (dy * dy + dz * dz) < r2;
    };
    for (int q = 0; q < rows.count; ++q) {
      uint32_t k = rows.begin[q];
      const uint32_t e = rows.end[q];
#if defined(__SSE2__)
      // Four candidates at a time (SSE's arithmetic is IEEE's lane by lane: `near`'s bits).
      const __m128 xx = _mm_set1_ps(xi.x()), xy = _mm_set1_ps(xi.y()), xz = _mm_set1_ps(xi.z()), rr = _mm_set1_ps(r2);
      for (; k + 4 <= e; k += 4) {
        const __m128 dx = _mm_sub_ps(xx, _mm_loadu_ps(X + k)), dy = _mm_sub_ps(xy, _mm_loadu_ps(Y + k));
        const __m128 dz = _mm_sub_ps(xz, _mm_loadu_ps(Z + k));
        const __m128 d2 = _mm_add_ps(_mm_mul_ps(dx, dx), _mm_add_ps(_mm_mul_ps(dy, dy), _mm_mul_ps(dz, dz)));
        const unsigned inside = unsigned(_mm_movemask_ps(_mm_cmplt_ps(d2, rr)));
        for (uint32_t l = 0; l < 4; ++l) {
          const uint32_t j = sorted[k + l];
          *out = j;
          out += ((inside >> l) & 1u) & unsigned(!(self && j == i));
        }
      }
#endif
      for (; k < e; ++k) {
        const uint32_t j = sorted[k];
        *out = j;
        out += near(k) & !(self && j == i);
      }
    }
    return size_t(out - base);
  });
}

void NeighborLists::build(const KdTree& tree, const std::vector<Vec3f>& x, float r, bool self) {
  static const std::vector<Vec3f> kNone;
  const std::vector<Vec3f>& y = tree.points() ? *tree.points() : kNone;
  const float r2 = r * r;
  fill(x.size(), nullptr, [&](size_t i, std::vector<uint32_t>& chunk, size_t at) {
    chunk.resize(at);
    if (y.empty()) return at;
    const Vec3f xi = x[i];
    const size_t before = at;
    tree.candidates(xi, r, chunk);
    // The grid's own test, so both searches agree on the pairs at |r_ij| ≈ h to the bit.
    auto keep = std::remove_if(chunk.begin() + long(before), chunk.end(), [&](uint32_t j) {
      return (self && j == i) || !((xi - y[j]).squaredNorm() < r2);
    });
    chunk.erase(keep, chunk.end());
    std::sort(chunk.begin() + long(before), chunk.end());
    return chunk.size();
  });
}

// nanoflann reads the points through this adaptor; it holds a pointer, not a copy.
struct KdTree::Impl {
  struct Cloud {
    const std::vector<Vec3f>* pts = nullptr;
    size_t kdtree_get_point_count() const { return pts ? pts->size() : 0; }
    float kdtree_get_pt(uint32_t i, size_t d) const { return (*pts)[i][Eigen::Index(d)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using Metric = nanoflann::L2_Simple_Adaptor<float, Cloud, float, uint32_t>;
  using Index = nanoflann::KDTreeSingleIndexAdaptor<Metric, Cloud, 3, uint32_t>;

  // Collects every index the search offers within the (widened) squared radius.
  struct Collector {
    float radius2;
    std::vector<uint32_t>& out;
    void init() {}
    size_t size() const { return out.size(); }
    bool full() const { return true; }
    bool addPoint(float d2, uint32_t j) {
      if (d2 <= radius2) out.push_back(j);
      return true;
    }
    float worstDist() const { return radius2; }
  };

  Cloud cloud;
  std::unique_ptr<Index> index;
};

KdTree::KdTree() : impl_(std::make_unique<Impl>()) {}
KdTree::~KdTree() = default;
KdTree::KdTree(KdTree&&) noexcept = default;
KdTree& KdTree::operator=(KdTree&&) noexcept = default;

void KdTree::build(const std::vector<Vec3f>& y) {
  impl_->cloud.pts = &y;
  // Leaves of ~16 points: about one particle's neighborhood at h = 2Δs per handful of leaves.
  if (!impl_->index) {
    impl_->index = std::make_unique<Impl::Index>(
        3, impl_->cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  } else {
    impl_->index->buildIndex();
  }
}

void KdTree::candidates(const Vec3f& p, float r, std::vector<uint32_t>& out) const {
  if (!impl_->index || impl_->cloud.kdtree_get_point_count() == 0) return;
  // Widened by 1e-4 relative: the tree's pruning rounds differently from the caller's exact test.
  Impl::Collector c{r * r * 1.0002f, out};
  const float q[3] = {p.x(), p.y(), p.z()};
  impl_->index->findNeighbors(c, q, nanoflann::SearchParams(32, 0.0f, false));
}

const std::vector<Vec3f>* KdTree::points() const { return impl_->cloud.pts; }

size_t KdTree::bytes() const {
  return impl_->index ? impl_->index->usedMemory(*impl_->index) : 0;
}

size_t NeighborLists::totalPairs() const {
  size_t s = 0;
  for (uint32_t c : count_) s += c;
  return s;
}

size_t NeighborLists::bytes() const {
  size_t s = first_.capacity() * sizeof(void*) + count_.capacity() * sizeof(uint32_t);
  for (const auto& c : chunks_) s += c.capacity() * sizeof(uint32_t);
  return s;
}

void Neighborhood::buildFluid(const std::vector<Vec3f>& x, float h, NeighborSearch method) {
  if (method == NeighborSearch::kKdTree) {
    // The paper's kd-tree, rebuilt every step; the same sets as the grid, in ascending index.
    fluidTree_.build(x);
    fluid_.build(fluidTree_, x, h, true);
    gridStale_ = true;
    return;
  }
  grid_.build(x, h);
  fluid_.build(grid_, x, x, grid_.start(), grid_.sorted(), h, true, inCellOrder_);
  gridStale_ = false;
}

void Neighborhood::buildBoundary(const std::vector<Vec3f>& fluid,
                                 const std::vector<Vec3f>& boundary, float h,
                                 NeighborSearch method) {
  if (method == NeighborSearch::kKdTree) {
    boundaryTree_.build(boundary);
    boundary_.build(boundaryTree_, fluid, h, false);
    return;
  }
  grid_.binOther(boundary, boundaryStart_, boundarySorted_);
  boundary_.build(grid_, fluid, boundary, boundaryStart_, boundarySorted_, h, false, inCellOrder_);
}

const Grid& Neighborhood::placementGrid(const std::vector<Vec3f>& x, float h) {
  if (gridStale_) grid_.build(x, h), gridStale_ = false;
  return grid_;
}

const Grid& Neighborhood::rebuildGrid(const std::vector<Vec3f>& x, float h) {
  grid_.build(x, h);
  return grid_;
}

size_t Neighborhood::bytes() const {
  return grid_.bytes() + fluidTree_.bytes() + boundaryTree_.bytes() + fluid_.bytes() +
         boundary_.bytes() + (boundaryStart_.capacity() + boundarySorted_.capacity()) * sizeof(uint32_t) +
         inCellOrder_.capacity() * sizeof(float);
}

}  // namespace scour
