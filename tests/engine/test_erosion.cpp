// Erosion (eqs. 9–10) and the terrain update (eqs. 21–22) in isolation.
#include <catch2/catch.hpp>
#include <omp.h>
#include <algorithm>
#include <cmath>

#include "engine/parallel.h"
#include "engine/sediment.h"

using namespace scour;

namespace {
struct OnePair {
  SimParams p;
  Fluid f;
  BoundaryParticles b;
  Grid grid;
  NeighborLists bn;
  std::vector<uint32_t> start, sorted;
  OnePair(float speed, float height) {
    p.spacing = 0.02;
    f.push(Vec3f(0.5f, height, 0.5f), Vec3f(speed, 0, 0), 0, 1000.0f);
    b.x.push_back(Vec3f(0.5f, 0.0f, 0.5f));
    b.triangle.push_back(7);
    b.area.push_back(3e-4);
    b.bary.emplace_back(0.3f, 0.3f);
    b.patch.push_back(-1);  // part of triangle 7
    b.extent.push_back(0);
    grid.build(f.x, float(p.support()));
    grid.binOther(b.x, start, sorted);
    bn.build(grid, f.x, b.x, start, sorted, float(p.support()), false);
  }
};
}  // namespace

TEST_CASE("a particle moving over one boundary particle erodes L_b² K_ε (τ − τ_c) Δt", "[erosion]") {
  OnePair s(2.0f, 0.01f);
  REQUIRE(s.bn.count(0) == 1);
  SedimentConstants k(s.p);
  TerrainAccumulator acc;
  acc.resize(16, 16);
  const double dt = 1e-3;
  erode(k, s.bn, s.b, dt, s.f, acc);
  const double l = double(s.f.x[0].y());  // distance to the boundary particle
  const double theta = 2.0 / l, tau = s.p.shear_k * std::pow(theta, s.p.shear_n);
  REQUIRE(tau > s.p.tau_c);
  const double mass = 3e-4 * s.p.k_eps * (tau - s.p.tau_c) * dt;
  const double volume = mass / s.p.sediment_density;
  CHECK(s.f.sed[0] == Approx(volume).epsilon(1e-12));
  // Exactly what the fluid gained: first the boundary particle's sum, then its triangle's.
  CHECK(acc.particle[0] == -s.f.sed[0]);
  CHECK(acc.particles == std::vector<uint32_t>{0});
  CHECK(acc.touched.empty());
  acc.spread(s.b);
  CHECK(acc.volume[7] == -s.f.sed[0]);
  CHECK(acc.touched == std::vector<int>{7});
  CHECK(acc.particles.empty());
  CHECK(acc.particle[0] == 0.0);
}

TEST_CASE("no erosion below the critical shear stress", "[erosion]") {
  // τ = K (v/l)^n ≤ τ_c: v = τ_c² l / K² at n = 1/2; go 1 % below.
  const float l = 0.01f;
  SimParams p;
  const float v = float(0.99 * std::pow(p.tau_c / p.shear_k, 2) * l);
  OnePair s(v, l);
  SedimentConstants k(s.p);
  TerrainAccumulator acc;
  acc.resize(16, 16);
  erode(k, s.bn, s.b, 1e-3, s.f, acc);
  CHECK(s.f.sed[0] == 0.0);
  CHECK(acc.particles.empty());
  acc.spread(s.b);
  CHECK(acc.touched.empty());
}

TEST_CASE("erosion over many boundary pairs: each pair's τ as eq. (9) gives it, the nearest one's the peak", "[erosion]") {
  // One fluid particle over boundary particles from well inside to well beyond the distance
  // l* = |v| K² / τ_c² where τ falls to τ_c (erode looks only at the pairs nearer than a millionth
  // beyond it): what it erodes and its peak are, to the bit, those of every pair's τ in list order.
  SimParams p;
  p.spacing = 0.02;
  const float speed = float(0.4 * p.support() * p.tau_c * p.tau_c / (p.shear_k * p.shear_k));
  const double lStar = double(speed) * p.shear_k * p.shear_k / (p.tau_c * p.tau_c);
  REQUIRE(lStar < 0.5 * p.support());
  Fluid f;
  f.push(Vec3f(0.5f, 0.0f, 0.5f), Vec3f(speed, 0, 0), 0, 1000.0f);
  BoundaryParticles b;
  for (double l : {0.001, 0.3 * lStar, lStar * (1 - 1e-7), lStar, lStar * (1 + 1e-7), lStar * (1 + 2e-6), 0.9 * p.support()}) {
    b.x.push_back(Vec3f(0.5f, -float(l), 0.5f));
    b.triangle.push_back(7), b.area.push_back(3e-4), b.bary.emplace_back(0.3f, 0.3f), b.patch.push_back(-1), b.extent.push_back(0);
  }
  Grid grid;
  grid.build(f.x, float(p.support()));
  std::vector<uint32_t> start, sorted;
  grid.binOther(b.x, start, sorted);
  NeighborLists bn;
  bn.build(grid, f.x, b.x, start, sorted, float(p.support()), false);
  REQUIRE(bn.count(0) == b.size());
  SedimentConstants k(p);
  TerrainAccumulator acc;
  acc.resize(16, 16);
  SedimentWorkspace ws;
  const double dt = 1e-3;
  erode(k, bn, b, dt, f, acc, ws);
  double peak = -1.0, total = 0.0;
  int eroding = 0;
  forEachNeighbor(bn, f.x, b.x, 0, [&](uint32_t bj, const Vec3f&, float r) {
    const double tau = p.shear_k * std::sqrt(double(speed) / std::max(double(r), k.min_distance));
    peak = std::max(peak, tau);
    if (tau <= p.tau_c) return;
    ++eroding;
    total += b.area[bj] * p.k_eps * (tau - p.tau_c) * dt / p.sediment_density;
  });
  CHECK(eroding >= 2);
  CHECK(eroding <= 4);
  CHECK(ws.tau[0] == float(peak));
  CHECK(f.sed[0] == total);
  CHECK(acc.particles.size() == size_t(eroding));
}

TEST_CASE("erosion stops at C_max", "[erosion]") {
  OnePair s(50.0f, 0.005f);
  s.b.area[0] = 1.0;  // a huge boundary particle: far more than a particle can carry
  SedimentConstants k(s.p);
  TerrainAccumulator acc;
  acc.resize(16, 16);
  erode(k, s.bn, s.b, 1e-2, s.f, acc);
  CHECK(s.f.sed[0] == Approx(s.p.c_max * k.volume).epsilon(1e-14));
  CHECK(acc.particle[0] == -s.f.sed[0]);
}

TEST_CASE("a block's boundary particle banks its step's sum, split over the block's triangles by area when applied", "[terrain]") {
  // A boundary particle standing for the 2 × 3 cells from cell (1, 2) of a grid 5 cells wide (a
  // terrain of 6 × 7 vertices, cells of 0.1 m): its sums wait whole in the block's first
  // triangle; applied, its 12 triangles get a twelfth each, the others nothing.
  Heightfield hf(6, 7, 0.1, 0.1);
  const auto areas = vertexAreas(hf);
  BoundaryParticles b;
  b.cellsX = 5;
  const int cell = 2 * 5 + 1, head = 2 * cell;
  const uint8_t extent = uint8_t(2 | 3 << 4);
  b.x.push_back(Vec3f::Zero()), b.triangle.push_back(head), b.area.push_back(1.0);
  b.bary.emplace_back(0.0f, 0.0f), b.patch.push_back(cell), b.extent.push_back(extent);
  TerrainAccumulator acc;
  acc.resize(hf.triangleCount(), hf.heights().size(), 5);
  // At a threshold of 1e-4 m the block of 0.06 m² takes its bank once |V| ≥ 6e-6 m³.
  const double threshold = 1e-4, least = threshold * 12 * 0.5 * 0.1 * 0.1;
  acc.addParticle(0, 3e-6);
  acc.addParticle(0, -1.2e-6);
  acc.addParticle(0, 0.6e-6);
  CHECK(acc.particles == std::vector<uint32_t>{0});
  const double sum = 3e-6 + -1.2e-6 + 0.6e-6;
  CHECK(acc.particle[0] == sum);
  acc.spread(b);
  CHECK(acc.touched == std::vector<int>{head});
  CHECK(acc.volume[size_t(head)] == sum);
  CHECK(acc.code[size_t(head)] == extent);
  CHECK(acc.waitingVolume() == sum);
  std::vector<int> expected;
  for (int k = 2; k < 5; ++k)
    for (int i = 1; i < 3; ++i) expected.push_back(2 * (k * 5 + i)), expected.push_back(2 * (k * 5 + i) + 1);
  std::vector<std::pair<int, double>> parts;
  acc.forEachWaiting([&](int t, double v) { parts.emplace_back(t, v); });
  REQUIRE(parts.size() == 12);
  for (size_t e = 0; e < 12; ++e) CHECK(parts[e] == std::make_pair(expected[e], sum / 12.0));
  // 2.4e-6 m³ is below the block's 6e-6: the bank waits whole, the terrain as it was.
  CHECK(applyTerrainChange(hf, areas, acc, threshold).empty());
  CHECK(acc.touched == std::vector<int>{head});
  CHECK(acc.volume[size_t(head)] == sum);
  // Two steps more carry it over: split by area, and every part applied.
  const Heightfield before = hf;
  for (int step = 0; step < 2; ++step) {
    acc.addParticle(0, 2e-6);
    acc.spread(b);
  }
  const double bank = sum + 2e-6 + 2e-6;
  REQUIRE(bank >= least);
  const std::vector<int> moved = applyTerrainChange(hf, areas, acc, threshold);
  CHECK(acc.touched.empty());
  for (int t = 0; t < hf.triangleCount(); ++t) {
    CHECK(acc.volume[size_t(t)] == 0.0);
    CHECK(acc.code[size_t(t)] == TerrainAccumulator::kNone);
  }
  CHECK(terrainVolume(hf, areas, 0.0) == Approx(bank).epsilon(1e-12));
  // The block's 4 × 3 vertices (1..3 along x, 2..5 along z) rose, no other.
  for (int k = 0; k < 7; ++k)
    for (int i = 0; i < 6; ++i) {
      const bool inside = i >= 1 && i <= 3 && k >= 2 && k <= 5;
      CHECK((hf.at(i, k) > before.at(i, k)) == inside);
      CHECK(acc.moved(k * 6 + i) == inside);
    }
  CHECK(moved.size() == 12);
}

TEST_CASE("a block's bank and a triangle's own sum on the same triangle: the bank is split first", "[terrain]") {
  // The terrain was sampled in other blocks since (a tile left and came back): a sum for one
  // triangle lands on a bank's head, and a bank on a triangle that holds its own sum.
  Heightfield hf(6, 7, 0.1, 0.1);
  const auto areas = vertexAreas(hf);
  TerrainAccumulator acc;
  acc.resize(hf.triangleCount(), hf.heights().size(), 5);
  const uint8_t wide = uint8_t(2 | 2 << 4), narrow = uint8_t(1 | 2 << 4);
  acc.addBlock(6, wide, 8e-6);  // cells 6, 7, 11, 12: triangles 12..15, 22..25
  acc.add(12, 1e-6);            // the head's own: the bank goes to its 8 triangles first
  CHECK(acc.code[12] == TerrainAccumulator::kTriangle);
  CHECK(acc.volume[12] == 1e-6 + 1e-6);
  for (int t : {13, 14, 15, 22, 23, 24, 25}) CHECK(acc.volume[size_t(t)] == 1e-6);
  acc.addBlock(6, narrow, 4e-6);  // the head holds a triangle's sum: split at once over 4
  for (int t : {12, 13, 22, 23}) CHECK(acc.code[size_t(t)] == TerrainAccumulator::kTriangle);
  CHECK(acc.volume[12] == 1e-6 + 1e-6 + 1e-6);
  CHECK(acc.volume[22] == 1e-6 + 1e-6);
  acc.addBlock(16, narrow, 2e-6);  // another bank, then a wider one with the same head
  acc.addBlock(16, wide, 4e-6);    // split over 8, the narrow bank with it
  CHECK(acc.code[32] == TerrainAccumulator::kTriangle);
  CHECK(acc.volume[32] == 2e-6 / 4 + 4e-6 / 8);
  CHECK(acc.volume[34] == 4e-6 / 8);
  const double total = 8e-6 + 1e-6 + 4e-6 + 2e-6 + 4e-6;
  CHECK(acc.waitingVolume() == Approx(total).epsilon(1e-15));
  applyTerrainChange(hf, areas, acc, 0.0);
  CHECK(acc.touched.empty());
  CHECK(terrainVolume(hf, areas, 0.0) == Approx(total).epsilon(1e-12));
}

TEST_CASE("a deposit raises the lowest vertex first and keeps the volume exact", "[terrain]") {
  Heightfield hf(4, 4, 0.5, 0.25);
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 4; ++i) hf.at(i, k) = 0.1 * i + 0.03 * k;
  auto areas = vertexAreas(hf);
  // The areas sum to the grid's area, edges and corners included.
  double total = 0;
  for (double a : areas) total += a;
  CHECK(total == Approx(1.5 * 0.75).epsilon(1e-14));
  const int tri = 2 * (1 * 3 + 1) + 0;  // cell (1,1), triangle 0: (1,1) (2,1) (2,2)
  auto verts = hf.triangleVertices(tri);
  const double v0 = terrainVolume(hf, areas, 0.0);
  const Heightfield before = hf;
  auto h = [&](const Heightfield& g, int a) { return g.at(verts[a][0], verts[a][1]); };
  auto area = [&](int a) { return areas[size_t(verts[a][1]) * 4 + verts[a][0]]; };
  // Lowest corner (1,1) at 0.13, next (2,1) at 0.23: a small deposit only lifts (1,1).
  double small = 0.5 * 0.1 * area(0);
  depositOnTriangle(hf, areas, tri, small);
  CHECK(terrainVolume(hf, areas, 0.0) - v0 == Approx(small).epsilon(1e-12));
  CHECK(h(hf, 0) == Approx(h(before, 0) + 0.05));
  CHECK(h(hf, 1) == h(before, 1));
  CHECK(h(hf, 2) == h(before, 2));
  // A large one levels all three and raises them together.
  double large = 1.0;
  depositOnTriangle(hf, areas, tri, large);
  CHECK(terrainVolume(hf, areas, 0.0) - v0 == Approx(small + large).epsilon(1e-12));
  CHECK(h(hf, 0) == Approx(h(hf, 1)).epsilon(1e-14));
  CHECK(h(hf, 1) == Approx(h(hf, 2)).epsilon(1e-14));
  // Erosion is symmetric: the highest corner is cut first.
  Heightfield g = before;
  const double cut = 0.5 * 0.03 * area(2);  // half of what levels (2,2) at 0.26 with (2,1) at 0.23
  depositOnTriangle(g, areas, tri, -cut);
  CHECK(terrainVolume(g, areas, 0.0) - v0 == Approx(-cut).epsilon(1e-12));
  CHECK(h(g, 2) == Approx(h(before, 2) - 0.015));
  CHECK(h(g, 0) == h(before, 0));
  CHECK(h(g, 1) == h(before, 1));
  // Untouched vertices stay untouched.
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 4; ++i) {
      bool corner = false;
      for (auto [vi, vk] : verts) corner = corner || (vi == i && vk == k);
      if (!corner) REQUIRE(g.at(i, k) == before.at(i, k));
    }
}

TEST_CASE("applyTerrainChange applies every triangle and reports the moved vertices", "[terrain]") {
  Heightfield hf(10, 10, 0.1, 0.1);
  auto areas = vertexAreas(hf);
  TerrainAccumulator acc;
  acc.resize(hf.triangleCount(), hf.heights().size());
  acc.add(40, 1e-3);
  acc.add(3, -2e-4);
  acc.add(40, 5e-4);
  acc.add(41, 2e-4);  // shares two vertices with 40
  acc.add(60, 0.0);   // touched, nothing to apply
  const Heightfield before = hf;
  auto moved = applyTerrainChange(hf, areas, acc);
  CHECK(terrainVolume(hf, areas, 0.0) == Approx(1.7e-3 - 2e-4).epsilon(1e-12));
  std::vector<int> once = moved;
  std::sort(once.begin(), once.end());
  CHECK(std::adjacent_find(once.begin(), once.end()) == once.end());  // each once
  // Exactly the vertices whose height changed are reported and marked.
  std::vector<int> changed;
  for (int v = 0; v < int(hf.heights().size()); ++v) {
    CHECK(acc.moved(v) == (hf.heights()[size_t(v)] != before.heights()[size_t(v)]));
    if (acc.moved(v)) changed.push_back(v);
  }
  CHECK(once == changed);
  // Triangle 3 (cell 1: vertices 1, 12, 11 of a flat terrain) cuts all three; 40 and 41 (cell 20,
  // vertices 22, 23, 32, 33) raise the four.
  CHECK(changed == std::vector<int>{1, 11, 12, 22, 23, 32, 33});
  CHECK(acc.touched.empty());
  CHECK(acc.volume[40] == 0.0);
  CHECK(acc.volume[41] == 0.0);
}

TEST_CASE("a triangle's volume waits until it would move the triangle by the threshold", "[terrain]") {
  // Cells of 0.1 m: a triangle of 5e-3 m². At a threshold of 1e-4 m a triangle takes its volume
  // once |V| ≥ 5e-7 m³; below that the volume waits, and the budget counts it as terrain.
  Heightfield hf(10, 10, 0.1, 0.1);
  auto areas = vertexAreas(hf);
  TerrainAccumulator acc;
  acc.resize(hf.triangleCount(), hf.heights().size());
  const double threshold = 1e-4, least = threshold * 0.5 * 0.1 * 0.1;
  acc.add(70, 0.6 * least);
  acc.add(12, -1.5 * least);
  acc.add(31, 0.99 * least);
  acc.add(5, 1.0 * least);
  const Heightfield before = hf;
  auto moved = applyTerrainChange(hf, areas, acc, threshold);
  // 12 and 5 are applied; 31 and 70 wait, in ascending order, their volumes kept to the bit.
  CHECK(acc.touched == std::vector<int>{31, 70});
  CHECK(acc.volume[31] == 0.99 * least);
  CHECK(acc.volume[70] == 0.6 * least);
  CHECK(acc.volume[12] == 0.0);
  CHECK(acc.volume[5] == 0.0);
  CHECK(terrainVolume(hf, areas, 0.0) == Approx(-0.5 * least).epsilon(1e-12));
  CHECK(terrainVolume(hf, areas, 0.0) + acc.waitingVolume() == Approx(1.09 * least).epsilon(1e-12));
  for (int v : hf.triangleVertexIndices(31)) CHECK(hf.heights()[v] == before.heights()[v]);
  CHECK(!moved.empty());
  // More on 70 carries it over: applied whole, the waiting volume with this step's.
  acc.add(70, 0.5 * least);
  acc.add(3, 0.1 * least);  // new, below: waits behind 31 in ascending order
  const double v70 = 0.6 * least + 0.5 * least;
  moved = applyTerrainChange(hf, areas, acc, threshold);
  CHECK(acc.touched == std::vector<int>{3, 31});
  CHECK(acc.volume[70] == 0.0);
  CHECK(terrainVolume(hf, areas, 0.0) == Approx(-0.5 * least + v70).epsilon(1e-12));
  CHECK(moved.size() == 3);  // 70's three corners, on flat ground
  // At threshold 0 every triangle is applied and nothing waits.
  applyTerrainChange(hf, areas, acc, 0.0);
  CHECK(acc.touched.empty());
  CHECK(terrainVolume(hf, areas, 0.0) == Approx(1.69 * least).epsilon(1e-12));
}

TEST_CASE("applyTerrainChange gives the same terrain at any thread count", "[terrain][determinism]") {
  // Volumes over many rows, in an order unrelated to the rows: each row in ascending order, the
  // even rows then the odd ones, whatever the threads. A small grid takes the rounds on one
  // thread (fewer touched triangles than kParallelFrom), the large one in parallel.
  const int side = GENERATE(60, 300);
  auto run = [side](int threads) {
    omp_set_num_threads(threads);
    Heightfield hf(side, side - 10, 0.02, 0.02);
    for (int k = 0; k < hf.nz(); ++k)
      for (int i = 0; i < hf.nx(); ++i) hf.at(i, k) = 0.01 * std::sin(0.3 * i) * std::cos(0.2 * k);
    auto areas = vertexAreas(hf);
    TerrainAccumulator acc;
    acc.resize(hf.triangleCount(), hf.heights().size());
    uint32_t seed = 11;
    for (int e = 0; e < std::max(20000, 2 * hf.triangleCount()); ++e) {
      seed = seed * 1664525u + 1013904223u;
      const int tri = int((seed >> 8) % uint32_t(hf.triangleCount()));
      acc.add(tri, 1e-7 * (double((seed >> 4) % 2001) - 1000.0));
    }
    if (side == 300) REQUIRE(acc.touched.size() >= 2 * kParallelFrom);
    const double v0 = terrainVolume(hf, areas, 0.0);
    double expected = 0;
    for (double v : acc.volume) expected += v;
    applyTerrainChange(hf, areas, acc);
    CHECK(terrainVolume(hf, areas, 0.0) - v0 == Approx(expected).epsilon(1e-10));
    return hf.heights();
  };
  const auto two = run(2);
  CHECK(run(1) == two);
  CHECK(run(3) == two);
  omp_set_num_threads(omp_get_num_procs());
}
