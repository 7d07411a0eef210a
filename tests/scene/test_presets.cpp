// The paper's scenes as presets: their grids and particle counts are the paper's, the canyon
// reads the SRTM tile built into the binary, and each runs (at a reduced scale) with erosion at
// work and no invariant broken. The terrain generators are deterministic and shaped as documented.
#include <catch2/catch.hpp>

#include <fstream>
#include <set>

#include "scene/assets.h"
#include "scene/presets.h"

using namespace scour;

TEST_CASE("the paper's scenes have the paper's grids and particle counts", "[presets]") {
  struct Expect {
    const char* name;
    int nx, nz;
    double particles;  // the paper's count
  };
  for (Expect e : {Expect{"canyon", 701, 351, 130000}, Expect{"lake", 201, 201, 90000},
                   Expect{"waterfall", 729, 513, 650000}}) {
    INFO(e.name);
    const Scene s = makePreset(e.name);
    CHECK(s.desc.terrain.nx() == e.nx);
    CHECK(s.desc.terrain.nz() == e.nz);
    const double n = double(s.desc.particles.size());
    CHECK(n > 0.85 * e.particles);
    CHECK(n < 1.15 * e.particles);
    // No particle starts inside the terrain.
    for (const auto& x : s.desc.particles)
      REQUIRE(x.y() >= s.desc.terrain.heightAt(x.x(), x.z()) + 0.49 * s.spec.params.spacing);
  }
}

TEST_CASE("the built-in SRTM tile is the file in assets/", "[presets]") {
  const Asset* a = findAsset("builtin:srtm-grand-canyon");
  REQUIRE(a != nullptr);
  std::ifstream in(std::string(SCOUR_SOURCE_DIR) + "/assets/srtm-grand-canyon-N36W113-r2400-c2400.png",
                   std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE(file.size() == a->size);
  CHECK(std::equal(file.begin(), file.end(), reinterpret_cast<const char*>(a->data)));
  // The canyon's terrain spans the heights it asks for, with 16-bit detail.
  const Scene s = makePreset("canyon", 0.05);
  const Heightfield& hf = s.desc.terrain;
  std::set<double> distinct(hf.heights().begin(), hf.heights().end());
  CHECK(distinct.size() > 10000);
  CHECK(hf.maxHeight() - hf.minHeight() > 1.2);  // 1.2 m of relief plus the tilt
}

TEST_CASE("the paper's scenes run and erode at a small scale", "[presets][slow]") {
  for (const char* name : {"canyon", "lake", "waterfall", "rain"}) {
    INFO(name);
    const Scene s = makePreset(name, 0.03);
    World w(s.desc);
    double moved = 0;
    for (int k = 0; k < 150; ++k) w.step();  // throws InvariantViolation on any breach
    for (double d : w.heightChange()) moved = std::max(moved, std::abs(d));
    CHECK(moved > 0);  // the terrain has been eroded somewhere
    CHECK(w.soilBudget().relativeError() < World::kSoilTolerance);
    CHECK(w.invariants().max_penetration_over_ds <= s.spec.params.max_penetration_over_ds);
  }
}

TEST_CASE("terrain generators are deterministic and shaped as documented", "[presets][terrain]") {
  TerrainSpec t = flatTerrain(4, 2, 0.05);
  t.kind = "terraces";
  t.slope = 0.3;  // a drop of 1.2 m in 3 steps of 0.4 m
  t.levels = 3;
  const Heightfield steps = buildTerrain(t);
  std::set<double> treads;
  for (int i = 0; i < steps.nx(); ++i) treads.insert(std::round(steps.at(i, steps.nz() / 2) * 1e6) / 1e6);
  CHECK(treads.count(0.0) == 1);
  CHECK(treads.count(0.4) == 1);
  CHECK(treads.count(0.8) == 1);
  CHECK(steps.maxHeight() == Approx(1.2));
  t.kind = "bowl";
  t.slope = 0;
  t.side_rise = 0.5;
  const Heightfield bowl = buildTerrain(t);
  CHECK(bowl.heightAt(2.0, 1.0) == Approx(0.0).margin(1e-12));  // the centre is the bottom
  CHECK(bowl.heightAt(2.0 + 0.8 * 1.0, 1.0) == Approx(0.5).epsilon(0.02));  // the rim
  t.kind = "fbm";
  t.side_rise = 0;
  t.noise.amplitude = 0.1;
  t.noise.feature = 0.5;
  t.noise.seed = 4;
  const Heightfield a = buildTerrain(t), b = buildTerrain(t);
  CHECK(a.heights() == b.heights());
  CHECK(a.maxHeight() - a.minHeight() > 0.05);
  CHECK(a.maxHeight() < 0.2);  // |fBm| ≤ amplitude · (1 + ½ + ¼ + …) < 2 · amplitude
  t.noise.seed = 5;
  CHECK(buildTerrain(t).heights() != a.heights());
}
