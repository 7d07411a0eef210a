#include "engine/neighbors.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/fluid.h"

namespace scour {

void Fluid::gather(const std::vector<uint32_t>& order) {
  auto apply = [&](auto& arr) {
    std::remove_reference_t<decltype(arr)> out(order.size());
    for (size_t k = 0; k < order.size(); ++k) out[k] = arr[order[k]];
    arr.swap(out);
  };
  apply(x);
  apply(v);
  apply(a);
  apply(rho);
  apply(p);
  apply(id);
  apply(sed);
}

Eigen::Vector3i Grid::cellOf(const Vec3f& p) const {
  Vec3f q = (p - origin_) / cell_;
  return {int(std::floor(q.x())), int(std::floor(q.y())), int(std::floor(q.z()))};
}

void Grid::build(const std::vector<Vec3f>& x, float cell) {
  cell_ = cell;
  const size_t n = x.size();
  Vec3f lo = Vec3f::Constant(std::numeric_limits<float>::max()), hi = -lo;
  if (n == 0) lo = hi = Vec3f::Zero();
  // min/max are exact, so the result does not depend on how the threads split the work.
#pragma omp parallel
  {
    Vec3f tlo = Vec3f::Constant(std::numeric_limits<float>::max()), thi = -tlo;
#pragma omp for schedule(static) nowait
    for (size_t i = 0; i < n; ++i) {
      tlo = tlo.cwiseMin(x[i]);
      thi = thi.cwiseMax(x[i]);
    }
#pragma omp critical
    {
      lo = lo.cwiseMin(tlo);
      hi = hi.cwiseMax(thi);
    }
  }
  origin_ = lo - Vec3f::Constant(cell);
  Vec3f ext = (hi - origin_) / cell;
  dims_ = {int(ext.x()) + 2, int(ext.y()) + 2, int(ext.z()) + 2};
  const size_t cells = size_t(dims_.x()) * dims_.y() * dims_.z();
  std::vector<int64_t> cellIdx(n);
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    Eigen::Vector3i c = cellOf(x[i]);
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
#pragma omp parallel for schedule(static)
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

void NeighborLists::build(const Grid& grid, const std::vector<Vec3f>& x,
                          const std::vector<Vec3f>& y, const std::vector<uint32_t>& start,
                          const std::vector<uint32_t>& sorted, float r, bool self) {
  const size_t n = x.size();
  const float r2 = r * r;
  first_.resize(n);
  count_.resize(n);
#pragma omp parallel
  {
    const int threads = omp_get_num_threads(), t = omp_get_thread_num();
#pragma omp single
    chunks_.resize(std::max<size_t>(chunks_.size(), size_t(threads)));
    // implicit barrier after single
    std::vector<uint32_t>& chunk = chunks_[t];
    chunk.clear();
    const size_t b = blockBegin(n, threads, t), e = blockBegin(n, threads, t + 1);
    for (size_t i = b; i < e; ++i) {
      const Vec3f xi = x[i];
      const size_t before = chunk.size();
      grid.forEachCandidate(xi, start, sorted, [&](uint32_t j) {
        if (self && j == i) return;
        if ((xi - y[j]).squaredNorm() < r2) chunk.push_back(j);
      });
      count_[i] = uint32_t(chunk.size() - before);
    }
    const uint32_t* p = chunk.data();
    for (size_t i = b; i < e; ++i) {
      first_[i] = p;
      p += count_[i];
    }
  }
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

}  // namespace scour
