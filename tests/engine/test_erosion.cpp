// Erosion (eqs. 9–10) and the terrain update (eqs. 21–22) in isolation.
#include <catch2/catch.hpp>
#include <cmath>

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
  acc.resize(16);
  const double dt = 1e-3;
  erode(k, s.bn, s.b, dt, s.f, acc);
  const double l = double(s.f.x[0].y());  // distance to the boundary particle
  const double theta = 2.0 / l, tau = s.p.shear_k * std::pow(theta, s.p.shear_n);
  REQUIRE(tau > s.p.tau_c);
  const double mass = 3e-4 * s.p.k_eps * (tau - s.p.tau_c) * dt;
  const double volume = mass / s.p.sediment_density;
  CHECK(s.f.sed[0] == Approx(volume).epsilon(1e-12));
  CHECK(acc.volume[7] == -s.f.sed[0]);  // exactly what the fluid gained
  CHECK(acc.touched == std::vector<int>{7});
}

TEST_CASE("no erosion below the critical shear stress", "[erosion]") {
  // τ = K (v/l)^n ≤ τ_c: v = τ_c² l / K² at n = 1/2; go 1 % below.
  const float l = 0.01f;
  SimParams p;
  const float v = float(0.99 * std::pow(p.tau_c / p.shear_k, 2) * l);
  OnePair s(v, l);
  SedimentConstants k(s.p);
  TerrainAccumulator acc;
  acc.resize(16);
  erode(k, s.bn, s.b, 1e-3, s.f, acc);
  CHECK(s.f.sed[0] == 0.0);
  CHECK(acc.touched.empty());
}

TEST_CASE("erosion stops at C_max", "[erosion]") {
  OnePair s(50.0f, 0.005f);
  s.b.area[0] = 1.0;  // a huge boundary particle: far more than a particle can carry
  SedimentConstants k(s.p);
  TerrainAccumulator acc;
  acc.resize(16);
  erode(k, s.bn, s.b, 1e-2, s.f, acc);
  CHECK(s.f.sed[0] == Approx(s.p.c_max * k.volume).epsilon(1e-14));
  CHECK(acc.volume[7] == -s.f.sed[0]);
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

TEST_CASE("applyTerrainChange applies every triangle and reports the moved ones", "[terrain]") {
  Heightfield hf(10, 10, 0.1, 0.1);
  auto areas = vertexAreas(hf);
  TerrainAccumulator acc;
  acc.resize(hf.triangleCount());
  acc.add(40, 1e-3);
  acc.add(3, -2e-4);
  acc.add(40, 5e-4);
  auto moved = applyTerrainChange(hf, areas, acc);
  CHECK(terrainVolume(hf, areas, 0.0) == Approx(1.5e-3 - 2e-4).epsilon(1e-12));
  std::vector<int> once = moved;
  std::sort(once.begin(), once.end());
  CHECK(std::adjacent_find(once.begin(), once.end()) == once.end());  // each once
  // The cells around cells 1 and 20 (of 9 × 9): 6 + 9, 2 of them shared; 2 triangles each.
  CHECK(moved.size() == 26);
  CHECK(std::find(moved.begin(), moved.end(), 40) != moved.end());
  CHECK(std::find(moved.begin(), moved.end(), 3) != moved.end());
  CHECK(acc.touched.empty());
  CHECK(acc.volume[40] == 0.0);
}
