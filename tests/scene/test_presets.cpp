// The paper's scenes as presets: their grids and particle counts are the paper's, the canyon
// reads the SRTM tile built into the binary, and each runs (at a reduced scale) with erosion at
// work and no invariant broken. The terrain generators are deterministic and shaped as documented.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <set>

#include "scene/assets.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_json.h"
#include "study/stress.h"
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

TEST_CASE("every built-in scene is its file in assets/scenes/, read by the scene reader",
          "[presets][builtin]") {
  const std::string dir = std::string(SCOUR_SOURCE_DIR) + "/assets/scenes/";
  size_t presets = 0, stress = 0;
  for (const BuiltinScene& b : builtinScenes()) {
    INFO(b.spec.name);
    b.stress ? ++stress : ++presets;
    const std::string stem = b.stress ? b.spec.name.substr(7) : b.spec.name;
    const std::string path = dir + (b.stress ? "stress/" : "") + stem + ".json";
    // The bytes built in are the file's, and the file read from disk is the same scene.
    std::ifstream in(path, std::ios::binary);
    const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const Asset* a = nullptr;
    for (const Asset& f : builtinSceneFiles())
      if (b.file == std::string("builtin:scenes/") + f.name) a = &f;
    REQUIRE(a != nullptr);
    CHECK(std::string(reinterpret_cast<const char*>(a->data), a->size) == file);
    CHECK(specToJson(loadSceneFile(path)) == specToJson(b.spec));
    CHECK(specToJson(presetSpec(b.spec.name)) == specToJson(b.spec));  // scale 1 changes nothing
    CHECK(!b.spec.description.empty());
    CHECK(b.stress == (b.spec.stress.duration > 0));  // the stress scenes say how long they run
  }
  CHECK(presets == presetList().size());
  CHECK(presets == 12);
  CHECK(stress == stressSceneNames().size());
  CHECK(stress == 22);
  REQUIRE_THROWS_WITH(presetSpec("nosuch"), Catch::StartsWith("unknown scene 'nosuch' (built-in scenes: block, canyon,") &&
                                                Catch::Contains("stress-cliffs"));
}

TEST_CASE("the default scene is a river worth showing: a fine grid, a source, the speed-up on", "[presets][builtin]") {
  // What a newcomer sees first (issue 16): at least 256 vertices along the river, finer than
  // the water, a source and a lake at its foot, and the bed at 100 times the water's clock
  // after the flow has settled. tests/cli/test_run_outputs.sh runs it and measures the cut.
  const Scene d = buildScene(presetSpec("default"));
  CHECK(d.desc.terrain.nx() >= 256);
  CHECK(d.desc.terrain.dx() < d.spec.params.spacing);
  CHECK(d.spec.sources.size() == 1);
  CHECK(d.spec.params.morphological_factor == 100);
  CHECK(d.spec.params.morphological_spinup == 0.5);
  CHECK(d.spec.has_camera);
  CHECK(d.desc.particles.size() > 500);  // the lake
}

TEST_CASE("each scene's scaling rule sets what --scale does", "[presets][builtin]") {
  // spacing: Δs / ∛scale, nothing else.
  const SceneSpec river = presetSpec("valley"), small = presetSpec("valley", 0.125);
  CHECK(small.params.spacing == Approx(2 * river.params.spacing));
  CHECK(specToJson(small)["terrain"] == specToJson(river)["terrain"]);
  // fixed: the lattice is the experiment.
  CHECK(specToJson(presetSpec("settling", 0.1)) == specToJson(presetSpec("settling")));
  // column: a whole number of cells across Martin & Moyce's column (at least 4), and a slab
  // six cells deep.
  for (double scale : {1.0, 0.3, 0.01, 1e-6}) {
    INFO("scale " << scale);
    const SceneSpec d = presetSpec("dambreak", scale);
    const double a = d.scaling.width, cells = a / d.params.spacing;
    CHECK(cells == Approx(std::round(cells)).epsilon(1e-12));
    CHECK(std::round(cells) == std::max(4.0, std::round(16 * std::cbrt(scale))));
    CHECK(d.terrain.length_z == Approx(6 * d.params.spacing));
    CHECK(d.blocks.at(0).max.z() == Approx(6 * d.params.spacing));
    CHECK(d.blocks.at(0).max.x() == a);
  }
  // pool: Δs as it is, the side to hold the count asked for in 16 layers.
  for (long n : {0L, 20000L, 500000L}) {
    INFO(n << " particles");
    const Scene b = buildScene(presetSpec("block", 1.0, n));
    const double want = n > 0 ? double(n) : 136000.0;
    CHECK(b.spec.params.spacing == 0.05);
    CHECK(double(b.desc.particles.size()) == Approx(want).epsilon(0.05));
    CHECK(b.spec.terrain.length_x == b.spec.blocks.at(0).max.x());
  }
  CHECK(double(buildScene(presetSpec("block", 0.25)).desc.particles.size()) ==
        Approx(0.25 * 136000).epsilon(0.05));
  REQUIRE_THROWS_WITH(presetSpec("valley", 0.0), "--scale must be a positive number");
}

TEST_CASE("every number's slider spans what a hand can drag and what the built-in scenes use",
          "[presets][params]") {
  for (const ParamInfo& p : paramTable()) {
    if (p.choices) continue;
    INFO(p.key);
    const SliderSpan s = sliderSpan(p);
    CHECK(s.lo >= p.min);
    CHECK(s.hi <= p.max);
    CHECK(s.lo < s.hi);
    // Wide spans are logarithmic, and no slider takes more than 6 decades: on a 300-pixel
    // slider a 150-pixel drag then changes a value at most 1,000-fold (Kε's old linear
    // [0, 10⁴] took 0.1 to 7,039).
    if (s.lo > 0 && s.hi / s.lo >= 100) CHECK(s.log);
    if (s.log) CHECK(s.hi / s.lo <= 1e6 * (1 + 1e-12));
    if (!s.log) CHECK((s.lo == 0 || s.hi / s.lo < 100));
    if (!s.log && s.lo == 0) CHECK(s.hi <= 1000 * std::max(getParam(SimParams{}, p), 1e-3));
    // The defaults and every built-in scene's values are on the slider (or are its off value,
    // typed with Ctrl+click, like Kε = 0).
    std::vector<std::pair<std::string, double>> uses = {{"defaults", getParam(SimParams{}, p)}};
    for (const BuiltinScene& b : builtinScenes())  // the stress scenes go past on purpose
      if (!b.stress) uses.emplace_back(b.spec.name, getParam(b.spec.params, p));
    for (const auto& [where, v] : uses) {
      INFO(where << ": " << v);
      CHECK(((v >= s.lo && v <= s.hi) || v == p.min));
    }
  }
}
