// Terrain queries and boundary particles: heights and normals of the two-triangle cells, the
// scanline sampling (areas add up to the triangle, points on the triangle), lazy tiles, and the
// no-slip friction of eqs. (7)–(8).
#include <catch2/catch.hpp>
#include <random>

#include <Eigen/Geometry>

#include "engine/boundary.h"
#include "engine/sediment.h"
#include "scene/presets.h"

using namespace scour;

TEST_CASE("a triangle's vertex indices are its corners (i, k) as k·nx + i", "[terrain]") {
  const Heightfield hf(7, 5, 0.1, 0.2);
  for (int t = 0; t < hf.triangleCount(); ++t) {
    const auto ik = hf.triangleVertices(t);
    const auto idx = hf.triangleVertexIndices(t);
    for (int a = 0; a < 3; ++a) CHECK(idx[size_t(a)] == size_t(ik[size_t(a)][1]) * 7 + size_t(ik[size_t(a)][0]));
  }
}

TEST_CASE("heightfield height and normal are those of the triangle under the point", "[terrain]") {
  // A plane h = 0.3 x − 0.2 z + 1 is reproduced exactly, with its normal.
  Heightfield hf(9, 7, 0.5, 0.25, -1.0, 2.0);
  for (int k = 0; k < hf.nz(); ++k)
    for (int i = 0; i < hf.nx(); ++i)
      hf.at(i, k) = 0.3 * (hf.x0() + i * hf.dx()) - 0.2 * (hf.z0() + k * hf.dz()) + 1.0;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(hf.x0(), hf.xMax()), uz(hf.z0(), hf.zMax());
  Eigen::Vector3d n = Eigen::Vector3d(-0.3, 1.0, 0.2).normalized();
  for (int t = 0; t < 200; ++t) {
    double x = ux(rng), z = uz(rng);
    SurfacePoint s = hf.surface(x, z);
    REQUIRE(s.height == Approx(0.3 * x - 0.2 * z + 1.0).margin(1e-12));
    REQUIRE((s.normal - n).norm() < 1e-12);
    // The triangle reported contains the point (in x–z).
    auto c = hf.triangleCorners(s.triangle);
    auto cross = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, double px, double pz) {
      return (b.x() - a.x()) * (pz - a.z()) - (b.z() - a.z()) * (px - a.x());
    };
    double s0 = cross(c[0], c[1], x, z), s1 = cross(c[1], c[2], x, z), s2 = cross(c[2], c[0], x, z);
    REQUIRE(((s0 >= -1e-12 && s1 >= -1e-12 && s2 >= -1e-12) ||
             (s0 <= 1e-12 && s1 <= 1e-12 && s2 <= 1e-12)));
  }
  // Outside the grid the query clamps to the edge.
  CHECK(hf.heightAt(-10.0, 2.0) == Approx(hf.at(0, 0)));
}

TEST_CASE("boundary particles cover each triangle with its exact area", "[boundary]") {
  Heightfield hf(6, 5, 0.3, 0.2);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 0.5);
  for (double& h : hf.heights()) h = u(rng);
  for (double spacing : {0.5, 0.1, 0.037}) {
    for (int tri = 0; tri < hf.triangleCount(); ++tri) {
      BoundaryParticles b;
      BoundarySampler::sampleTriangle(hf, tri, spacing, b);
      auto c = hf.triangleCorners(tri);
      double projected = 0.5 * std::abs((c[1] - c[0]).x() * (c[2] - c[0]).z() -
                                        (c[1] - c[0]).z() * (c[2] - c[0]).x());
      double sum = 0;
      for (double a : b.area) sum += a;
      REQUIRE(sum == Approx(projected).epsilon(1e-12));
      double area3d = 0.5 * (c[1] - c[0]).cross(c[2] - c[0]).norm();
      int n = std::max(1, int(std::lround(std::sqrt(area3d) / spacing)));
      REQUIRE(b.size() == size_t(n) * n);
      for (size_t k = 0; k < b.size(); ++k) {
        REQUIRE(b.triangle[k] == tri);
        // On the triangle's plane: the heightfield under the point is the point's height.
        Eigen::Vector3d p = b.x[k].cast<double>();
        REQUIRE(hf.surface(p.x(), p.z()).triangle == tri);
        REQUIRE(hf.heightAt(p.x(), p.z()) == Approx(p.y()).margin(1e-6));
      }
    }
  }
}

TEST_CASE("boundary particles exist only for tiles near water", "[boundary]") {
  Heightfield hf(65, 65, 0.1, 0.1);  // 8 × 8 tiles of 8 × 8 cells
  BoundarySampler sampler(hf, 0.05, BoundarySampling::kTriangles);
  std::vector<Vec3f> fluid = {Vec3f(0.35f, 0.05f, 0.35f), Vec3f(0.36f, 0.06f, 0.34f),
                              Vec3f(5.0f, 3.0f, 5.0f)};  // the last one is far above the ground
  REQUIRE(sampler.updateActiveTiles(hf, fluid, 0.1));
  CHECK(sampler.activeTiles() == std::vector<int>{0});
  BoundaryParticles b;
  sampler.generate(hf, b);
  CHECK(b.size() == size_t(8 * 8 * 2 * 1));  // 128 triangles of 0.005 m²: n = round(0.07/0.05) = 1
  CHECK_FALSE(sampler.updateActiveTiles(hf, fluid, 0.1));  // unchanged set
  fluid.push_back(Vec3f(0.79f, 0.0f, 0.2f));  // within reach of tile 1 (x from 0.8)
  REQUIRE(sampler.updateActiveTiles(hf, fluid, 0.1));
  CHECK(sampler.activeTiles() == std::vector<int>{0, 1});
}

TEST_CASE("a tile that stays active keeps its particles; a new one is sampled", "[boundary]") {
  Heightfield hf(65, 65, 0.1, 0.1);
  BoundarySampler sampler(hf, 0.05, BoundarySampling::kTriangles);
  std::vector<Vec3f> fluid = {Vec3f(0.35f, 0.05f, 0.35f)};
  REQUIRE(sampler.updateActiveTiles(hf, fluid, 0.1));
  BoundaryParticles b;
  sampler.generate(hf, b);
  REQUIRE(b.size() == 128);
  // The terrain under tile 0 moves; its particles are marked as having followed it (a lift the
  // sampler would not make), so a resample would show.
  for (size_t j = 0; j < b.size(); ++j) b.x[j].y() += 0.25f;
  const BoundaryParticles tile0 = b;
  fluid.push_back(Vec3f(1.2f, 0.0f, 0.2f));  // tile 1 (x from 0.8 to 1.6) alone
  REQUIRE(sampler.updateActiveTiles(hf, fluid, 0.1));
  REQUIRE(sampler.activeTiles() == std::vector<int>{0, 1});
  sampler.generate(hf, b);
  REQUIRE(b.size() == 256);
  for (size_t j = 0; j < 128; ++j) {
    CHECK(b.x[j] == tile0.x[j]);  // kept, not resampled
    CHECK(b.triangle[j] == tile0.triangle[j]);
  }
  // Tile 1's particles are those a fresh sampling of it gives, after tile 0's.
  BoundaryParticles fresh;
  fresh.cellsX = 64;
  BoundarySampler::sampleCells(hf, 8, 0, 16, 8, 0.05, fresh);
  REQUIRE(fresh.size() == 128);
  for (size_t j = 0; j < 128; ++j) {
    CHECK(b.x[128 + j] == fresh.x[j]);
    CHECK(b.area[128 + j] == fresh.area[j]);
  }
  // Tile 0 leaves: only tile 1's particles stay, unchanged.
  fluid.erase(fluid.begin());
  REQUIRE(sampler.updateActiveTiles(hf, fluid, 0.1));
  REQUIRE(sampler.activeTiles() == std::vector<int>{1});
  sampler.generate(hf, b);
  REQUIRE(b.size() == 128);
  for (size_t j = 0; j < 128; ++j) CHECK(b.x[j] == fresh.x[j]);
}

TEST_CASE("no-slip friction slows water down the slope", "[boundary][physics]") {
  auto meanSpeed = [](double friction) {
    Scene s = makePreset("slope", 0.25);
    s.desc.params.boundary_friction = friction;
    World w(s.desc);
    for (int k = 0; k < 300; ++k) w.step();
    double v = 0;
    for (const auto& u : w.fluid().v) v += u.norm();
    return v / double(w.fluid().size());
  };
  double free = meanSpeed(0.0), sticky = meanSpeed(2e-4);
  INFO("mean speed without friction " << free << " m/s, with μ_b = 2e-4: " << sticky << " m/s");
  CHECK(free > 0.3);
  // Measured: 0.80 of the free speed (0.79 before the CFL step followed the compressed sound
  // speed, which shortens it by about 3 %); without friction at work the ratio would be 1.
  CHECK(sticky < 0.85 * free);
}

TEST_CASE("the wall surface is the terrain's envelope, never below it, and follows it", "[boundary]") {
  // Needles: every vertex a random height within ±4 cells, on a grid of 1 cm.
  Heightfield t(41, 31, 0.01, 0.01);
  uint32_t seed = 7;
  for (double& y : t.heights()) {
    seed = seed * 1664525u + 1013904223u;
    y = 0.04 * double(seed >> 8) / double(1 << 24);
  }
  const WallSurface w(t, 0.01);  // a radius of one cell: the disk is the vertex and its 4 nearest
  REQUIRE(w.filters());
  double roughT = 0, roughW = 0;
  for (int k = 0; k < t.nz(); ++k)
    for (int i = 0; i < t.nx(); ++i) {
      REQUIRE(w.of(t).at(i, k) >= t.at(i, k));
      if (i == 0) continue;
      roughT += std::abs(t.at(i, k) - t.at(i - 1, k));
      roughW += std::abs(w.of(t).at(i, k) - w.of(t).at(i - 1, k));
    }
  CHECK(roughW < 0.5 * roughT);  // the needles are gone
  // A vertex in the middle: the mean of the maxima over its 5-point disk, by hand.
  auto mx = [&](int i, int k) {
    return std::max({t.at(i, k), t.at(i - 1, k), t.at(i + 1, k), t.at(i, k - 1), t.at(i, k + 1)});
  };
  const double mean = (mx(10, 10) + mx(9, 10) + mx(11, 10) + mx(10, 9) + mx(10, 11)) / 5;
  CHECK(w.of(t).at(10, 10) == Approx(mean));

  // Erosion moves two vertices: following them gives what a rebuild gives, to the bit.
  Heightfield moved = t;
  moved.at(20, 15) += 0.05, moved.at(21, 16) -= 0.03;
  WallSurface followed = w;
  followed.follow(moved, {15 * 41 + 20, 16 * 41 + 21});
  CHECK(followed.of(moved).heights() == WallSurface(moved, 0.01).of(moved).heights());

  // A grid coarser than the radius: the terrain itself, not a copy.
  const WallSurface coarse(t, 0.009);
  CHECK_FALSE(coarse.filters());
  CHECK(&coarse.of(t) == &t);
}

TEST_CASE("spacing sampling: one boundary particle per block of cells about Δs wide", "[boundary]") {
  // Cells of 1 cm under Δs = 2.1 cm: blocks of 2 × 2 cells; a grid coarser than 2^(−1/4) Δs keeps
  // a particle per triangle.
  Heightfield hf(65, 65, 0.01, 0.01);
  CHECK(BoundarySampler::blockCells(hf, 0.021) == 2);
  CHECK(BoundarySampler::blockCells(hf, 0.009) == 1);
  // Rounded in ratio: 2 cells once Δs / cell passes √2 (the canyon at scale 0.3: 1.49), 3 past √6.
  CHECK(BoundarySampler::blockCells(hf, 0.0141) == 1);
  CHECK(BoundarySampler::blockCells(hf, 0.0149) == 2);
  CHECK(BoundarySampler::blockCells(hf, 0.0244) == 2);
  CHECK(BoundarySampler::blockCells(hf, 0.0246) == 3);
  CHECK(BoundarySampler::blockCells(hf, 0.008) == 0);
  CHECK(BoundarySampler::blockCells(hf, 0.5) == BoundarySampler::kTileCells);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 0.004);
  for (double& h : hf.heights()) h = u(rng);  // rough, finer than Δs, but not steep
  // A cliff through the blocks of cells (4–5, ·): 12 cm up from vertex column 5 on.
  for (int k = 0; k < hf.nz(); ++k)
    for (int i = 5; i < hf.nx(); ++i) hf.at(i, k) += 0.12;
  BoundarySampler sampler(hf, 0.021, BoundarySampling::kSpacing);
  REQUIRE(sampler.block() == 2);
  REQUIRE(sampler.updateActiveTiles(hf, {Vec3f(0.03f, 0.01f, 0.03f)}, 0.02));
  REQUIRE(sampler.activeTiles() == std::vector<int>{0});
  BoundaryParticles b;
  sampler.generate(hf, b);
  // 16 blocks of the 8 × 8 cells; the 4 along the cliff (cells i = 4, 5) are too steep for one
  // particle and are halved: the cells on top (i = 5) one particle each, the riser's (i = 4, 12 cm
  // over 1 cm) by triangle.
  size_t blocks = 0, cells = 0, byTriangle = 0;
  double area = 0;
  for (size_t j = 0; j < b.size(); ++j) {
    area += b.area[j];
    const Eigen::Vector3d p = b.x[j].cast<double>();
    CHECK(hf.heightAt(p.x(), p.z()) == Approx(p.y()).margin(1e-6));  // on the terrain
    CHECK(hf.distanceToTriangle(b.triangle[j], p) < 1e-6);  // on the triangle it follows
    if (b.patch[j] < 0) {
      ++byTriangle;
      const int cell = b.triangle[j] / 2;
      CHECK(cell % 64 == 4);
      continue;
    }
    if (b.extent[j] == (1 | 1 << 4)) {
      ++cells;
      CHECK(b.patch[j] % 64 == 5);
      CHECK(b.area[j] == Approx(1e-4).epsilon(1e-12));
      CHECK(p.x() == Approx(0.055).margin(1e-7));
      CHECK(p.z() == Approx(0.01 * (b.patch[j] / 64 + 0.5)).margin(1e-7));
      continue;
    }
    ++blocks;
    CHECK(b.extent[j] == (2 | 2 << 4));
    CHECK(b.area[j] == Approx(4e-4).epsilon(1e-12));
    // At the block's centre: its first cell's far corner.
    const int i0 = b.patch[j] % 64, k0 = b.patch[j] / 64;
    CHECK(i0 % 2 == 0);
    CHECK(k0 % 2 == 0);
    CHECK(p.x() == Approx(0.01 * (i0 + 1)).margin(1e-7));
    CHECK(p.z() == Approx(0.01 * (k0 + 1)).margin(1e-7));
  }
  CHECK(blocks == 12);
  CHECK(cells == 8);
  CHECK(byTriangle == 8 * 2);
  CHECK(area == Approx(0.08 * 0.08).epsilon(1e-12));  // the tile's area, exactly covered
  // What a block particle exchanges goes to its 8 triangles in equal parts, summing to it.
  const size_t j = size_t(std::find_if(b.patch.begin(), b.patch.end(), [](int q) { return q >= 0; }) - b.patch.begin());
  std::vector<std::pair<int, double>> parts;
  TerrainAccumulator acc;
  acc.cellsX = b.cellsX;
  acc.forEachBlockTriangle(b.patch[j], b.extent[j], -3e-7, [&](int tri, double v) { parts.emplace_back(tri, v); });
  REQUIRE(parts.size() == 8);
  double sum = 0;
  for (auto [tri, v] : parts) {
    sum += v;
    CHECK(v == -3e-7 / 8);
    const int cell = tri / 2, i = cell % 64, k = cell / 64;
    CHECK((i - b.patch[j] % 64 >= 0 && i - b.patch[j] % 64 < 2 && k - b.patch[j] / 64 >= 0 && k - b.patch[j] / 64 < 2));
  }
  CHECK(sum == Approx(-3e-7).epsilon(1e-15));
}
