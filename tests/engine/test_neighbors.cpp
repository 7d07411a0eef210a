// The uniform-grid neighbor search against brute force, on random sets that include particles
// exactly on cell borders and at the edges of the bounding box.
#include <catch2/catch.hpp>
#include <algorithm>
#include <random>
#include <omp.h>

#include "engine/neighbors.h"

using namespace scour;

namespace {
std::vector<std::vector<uint32_t>> bruteForce(const std::vector<Vec3f>& x, const std::vector<Vec3f>& y,
                                              float r, bool self) {
  std::vector<std::vector<uint32_t>> out(x.size());
  for (size_t i = 0; i < x.size(); ++i)
    for (size_t j = 0; j < y.size(); ++j)
      if (!(self && i == j) && (x[i] - y[j]).squaredNorm() < r * r) out[i].push_back(uint32_t(j));
  return out;
}

std::vector<std::vector<uint32_t>> fromLists(const NeighborLists& n) {
  std::vector<std::vector<uint32_t>> out(n.size());
  for (size_t i = 0; i < n.size(); ++i) {
    out[i].assign(n.begin(i), n.begin(i) + n.count(i));
    std::sort(out[i].begin(), out[i].end());
  }
  return out;
}
}  // namespace

TEST_CASE("grid neighbor search equals brute force", "[neighbors]") {
  std::mt19937 rng(42);
  const float h = 0.1f;
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  std::uniform_int_distribution<int> cellPick(-5, 5);
  std::vector<Vec3f> x;
  for (int i = 0; i < 1500; ++i) x.emplace_back(u(rng), u(rng), u(rng));
  // Points exactly on cell borders (multiples of h from the lower bound) and on the box edges.
  for (int i = 0; i < 300; ++i)
    x.emplace_back(cellPick(rng) * h, cellPick(rng) * h + 0.5f * u(rng), cellPick(rng) * h);
  for (float e : {-0.5f, 0.5f}) x.emplace_back(e, e, e), x.emplace_back(e, -e, 0.0f);
  x.push_back(x[7]);  // a duplicate position: distance 0 is a neighbor too

  Grid g;
  g.build(x, h);
  NeighborLists n;
  n.build(g, x, x, g.start(), g.sorted(), h, true);
  auto expect = bruteForce(x, x, h, true);
  REQUIRE(fromLists(n) == expect);
  size_t pairs = 0;
  for (auto& l : expect) pairs += l.size();
  CHECK(n.totalPairs() == pairs);
  CHECK(pairs > 10000);  // the test exercises dense neighborhoods

  SECTION("a second point set (boundary particles) binned into the same grid") {
    std::vector<Vec3f> y;
    for (int i = 0; i < 800; ++i) y.emplace_back(1.3f * u(rng), 1.3f * u(rng), 1.3f * u(rng));
    std::vector<uint32_t> start, sorted;
    g.binOther(y, start, sorted);
    NeighborLists nb;
    nb.build(g, x, y, start, sorted, h, false);
    REQUIRE(fromLists(nb) == bruteForce(x, y, h, false));
  }
  SECTION("lists are ordered the same at 1 and 2 threads") {
    NeighborLists a, b;
    omp_set_num_threads(1);
    a.build(g, x, x, g.start(), g.sorted(), h, true);
    omp_set_num_threads(2);
    b.build(g, x, x, g.start(), g.sorted(), h, true);
    for (size_t i = 0; i < x.size(); ++i)
      REQUIRE(std::equal(a.begin(i), a.begin(i) + a.count(i), b.begin(i), b.begin(i) + b.count(i)));
  }
}

TEST_CASE("the Z-order permutation is a permutation and groups cells", "[neighbors]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Vec3f> x;
  for (int i = 0; i < 5000; ++i) x.emplace_back(u(rng), u(rng), u(rng));
  Grid g;
  g.build(x, 0.05f);
  auto order = g.zOrder(x);
  auto sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (size_t k = 0; k < sorted.size(); ++k) REQUIRE(sorted[k] == k);
  // Along the curve, consecutive particles are mostly in the same or adjacent cells.
  size_t near = 0;
  for (size_t k = 1; k < order.size(); ++k) {
    Eigen::Vector3i a = g.cellOf(x[order[k - 1]]), b = g.cellOf(x[order[k]]);
    if ((a - b).cwiseAbs().maxCoeff() <= 1) ++near;
  }
  CHECK(near > 0.8 * order.size());
}
