// The erosion maps (engine/maps.h, issue 17) agree with the soil ledger: Σ wear × vertex area is
// the eroded volume, Σ deposition × area the deposited volume, Σ sediment × area the suspended
// volume, each to 1e-9 relative; every value is ≥ 0, and a vertex is never both worn and built.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <omp.h>

#include "engine/flow_record.h"
#include "engine/maps.h"
#include "engine/world.h"
#include "engine/sediment.h"
#include "scene/presets.h"

using namespace scour;

namespace {
// The valley river at N = 20 after a short spin-up: erosion and deposition under way in a few
// hundred steps.
SceneSpec quickValley() {
  SceneSpec spec = presetSpec("valley", 0.3);
  spec.params.morphological_factor = 20;
  spec.params.morphological_spinup = 0.02;
  return spec;
}
}  // namespace

TEST_CASE("the erosion maps sum to the ledger's volumes", "[maps][budget]") {
  const SceneSpec spec = quickValley();
  World w(buildScene(spec).desc);
  for (int k = 0; k < 250; ++k) w.step();
  const std::vector<TerrainMap> maps = erosionMaps(w);
  REQUIRE(maps.size() == 8);
  CHECK(maps[0].name == "wear");
  CHECK(maps[1].name == "deposition");
  CHECK(maps[2].name == "sediment");
  const std::vector<double>& area = w.vertexArea();
  const TerrainChange change = measureTerrainChange(w.heightChange(), area);
  REQUIRE(change.eroded > 0);
  REQUIRE(change.deposited > 0);
  double wear = 0, deposition = 0, sediment = 0, suspended = 0;
  for (size_t v = 0; v < area.size(); ++v) {
    CHECK((maps[0].values[v] >= 0 && maps[1].values[v] >= 0 && maps[2].values[v] >= 0));
    CHECK((maps[0].values[v] == 0 || maps[1].values[v] == 0));
    wear += maps[0].values[v] * area[v];
    deposition += maps[1].values[v] * area[v];
    sediment += maps[2].values[v] * area[v];
  }
  for (size_t i = 0; i < w.fluid().size(); ++i) suspended += w.fluid().sed[i];
  REQUIRE(suspended > 0);
  CHECK(std::abs(wear / change.eroded - 1) < 1e-9);
  CHECK(std::abs(deposition / change.deposited - 1) < 1e-9);
  CHECK(std::abs(sediment / suspended - 1) < 1e-9);
  CHECK(std::abs(suspended / w.soilBudget().suspended - 1) < 1e-9);
  // The sediment is where the particles carrying it are: a vertex holds some only when a particle
  // with sediment stands over one of the cells around it, and the vertex nearest each such
  // particle holds some (a transposed or shifted map fails this).
  const Heightfield& hf = w.terrain();
  const Fluid& f = w.fluid();
  std::vector<char> near(area.size(), 0);
  for (size_t i = 0; i < f.size(); ++i) {
    if (f.sed[i] <= 0) continue;
    const double u = std::clamp((f.x[i].x() - hf.x0()) / hf.dx(), 0.0, double(hf.nx() - 1));
    const double q = std::clamp((f.x[i].z() - hf.z0()) / hf.dz(), 0.0, double(hf.nz() - 1));
    for (int k = int(std::floor(q)); k <= int(std::ceil(q)); ++k)
      for (int c = int(std::floor(u)); c <= int(std::ceil(u)); ++c) near[size_t(k) * hf.nx() + c] = 1;
    const size_t nearest = size_t(std::lround(q)) * hf.nx() + size_t(std::lround(u));
    CHECK(maps[2].values[nearest] > 0);
  }
  for (size_t v = 0; v < area.size(); ++v)
    if (maps[2].values[v] > 0) CHECK(near[v]);
  // The deepest cut is the wear map's peak.
  double peak = 0;
  for (double v : maps[0].values) peak = std::max(peak, v);
  CHECK(peak == change.max_erosion);
}

TEST_CASE("the flow record shares each near-bed particle's flux over its footprint", "[maps]") {
  // A 5 × 5 grid of 0.1 m cells; Δs = 0.25 m covers the vertices within 0.125 m of the particle.
  Heightfield hf(5, 5, 0.1, 0.1);
  const std::vector<double> area = vertexAreas(hf);
  Fluid f;
  f.push(Vec3f(0.2f, 0.05f, 0.2f), Vec3f(2.0f, 0.0f, -1.0f), 0, 1000.0f);  // near the bed
  f.push(Vec3f(0.4f, 0.05f, 0.0f), Vec3f(5.0f, 0.0f, 0.0f), 1, 1000.0f);   // not (τ < 0)
  const std::vector<float> tau = {3.0f, -1.0f};
  FlowRecord r;
  r.record(hf, area, f, tau, 1e-3, 0.25, 0.5);
  r.record(hf, area, f, {1.0f, -1.0f}, 1e-3, 0.25, 1.5);
  CHECK(r.time() == 2.0);
  const std::vector<double> wet = r.wetTime(), qx = r.flowX(), qz = r.flowZ(), flow = r.flow();
  const std::vector<double> peak = r.shearPeak(), shear = r.shearIntegral();
  double sx = 0, sz = 0;
  for (int k = 0; k < 5; ++k)
    for (int i = 0; i < 5; ++i) {
      const size_t v = size_t(k) * 5 + size_t(i);
      const bool covered = i >= 1 && i <= 3 && k >= 1 && k <= 3;
      CHECK(wet[v] == (covered ? 2.0 : 0.0));
      CHECK(peak[v] == (covered ? 3.0 : 0.0));
      CHECK(shear[v] == Approx(covered ? 3.0 * 0.5 + 1.0 * 1.5 : 0.0));
      CHECK(flow[v] == Approx(std::hypot(qx[v], qz[v])).epsilon(1e-12));
      sx += qx[v] * area[v], sz += qz[v] * area[v];
    }
  // Σ q A over the run is the particle's V v over the bed time.
  CHECK(sx == Approx(1e-3 * 2.0 * 2.0).epsilon(1e-12));
  CHECK(sz == Approx(1e-3 * -1.0 * 2.0).epsilon(1e-12));
  // Only the tile the water touched holds memory.
  CHECK(r.tiles().size() == 1);
}

TEST_CASE("the flow maps: wetness in [0, 1], dry vertices without flow or shear", "[maps]") {
  const SceneSpec spec = quickValley();
  World w(buildScene(spec).desc);
  for (int k = 0; k < 150; ++k) w.step();
  const std::vector<TerrainMap> maps = erosionMaps(w);
  auto map = [&](const std::string& name) -> const TerrainMap& {
    return *std::find_if(maps.begin(), maps.end(), [&](const TerrainMap& m) { return m.name == name; });
  };
  const TerrainMap &flow = map("flow"), &wet = map("wetness"), &peak = map("shear_peak"), &mean = map("shear_mean"),
                   &dir = map("flow_direction");
  REQUIRE(dir.second.size() == dir.values.size());
  size_t wetCount = 0, alwaysWet = 0;
  for (size_t v = 0; v < wet.values.size(); ++v) {
    REQUIRE(wet.values[v] >= 0.0);
    REQUIRE(wet.values[v] <= 1.0);
    if (wet.values[v] == 0.0) {
      CHECK(flow.values[v] == 0.0);
      CHECK(peak.values[v] == 0.0);
      CHECK(mean.values[v] == 0.0);
      CHECK((dir.values[v] == 0.0 && dir.second[v] == 0.0));
      continue;
    }
    ++wetCount;
    alwaysWet += wet.values[v] == 1.0;
    CHECK(mean.values[v] <= peak.values[v] * (1 + 1e-12));
    const double len = std::hypot(dir.values[v], dir.second[v]);
    CHECK((len == 0.0 || std::abs(len - 1.0) < 1e-12));
  }
  // The river: wet along its bed, dry on the valley's sides, and flowing downhill (the valley
  // falls along +x) on the whole.
  CHECK(wetCount > 100);
  CHECK(alwaysWet > 0);
  CHECK(wetCount < wet.values.size() / 2);
  double down = 0;
  for (size_t v = 0; v < wet.values.size(); ++v) down += flow.values[v] * dir.values[v];
  CHECK(down > 0);
  CHECK(w.flowRecord().time() == Approx(w.morphologicalTime()).epsilon(1e-12));
}

TEST_CASE("the flow record: the same at 1 and 2 threads, through a saved state", "[maps][determinism]") {
  const SceneSpec spec = quickValley();
  auto run = [&](int threads, bool viaState) {
    omp_set_num_threads(threads);
    World w(buildScene(spec).desc);
    for (int k = 0; k < 60; ++k) w.step();
    if (viaState) {
      std::stringstream s;
      w.saveState(s);
      World again(buildScene(spec).desc);
      again.loadState(s);
      for (int k = 0; k < 40; ++k) again.step();
      return again.flowRecord().values();
    }
    for (int k = 0; k < 40; ++k) w.step();
    return w.flowRecord().values();
  };
  const std::vector<double> one = run(1, false), two = run(2, false), resumed = run(2, true);
  omp_set_num_threads(2);
  REQUIRE(!one.empty());
  CHECK(one == two);
  CHECK(one == resumed);
}

TEST_CASE("a corrupt flow record in a state is refused", "[maps]") {
  FlowRecord r;
  r.reset(40, 40);
  const size_t perTile = 6 * FlowRecord::kTile * FlowRecord::kTile;
  CHECK_THROWS_WITH(r.restore(40, 40, 1.0, {25}, std::vector<double>(perTile, 0.0)), "state is corrupt (flow maps)");
  CHECK_THROWS_WITH(r.restore(40, 40, 1.0, {1, 1}, std::vector<double>(2 * perTile, 0.0)), "state is corrupt (flow maps)");
  CHECK_THROWS_WITH(r.restore(40, 40, 1.0, {1}, std::vector<double>(perTile, -1.0)), "state is corrupt (flow maps)");
  CHECK_THROWS_WITH(r.restore(40, 40, -1.0, {}, {}), "state is corrupt (flow maps)");
  r.restore(40, 40, 2.0, {3}, std::vector<double>(perTile, 0.25));
  CHECK(r.time() == 2.0);
  CHECK(r.tiles() == std::vector<int>{3});
}

TEST_CASE("a version 7 flow record (tiles of 16 vertices) loads into this build's tiles", "[maps]") {
  // 40 × 40 vertices: 3 × 3 tiles of 16, the last row and column of them cut by the grid's edge.
  // Tile 4 (vertices 16–31 along both axes) and tile 8 (32–39) hold values; of tile 4 only the
  // quarter at x 16–23, z 24–31 is non-zero, so one tile of 8 comes of it.
  constexpr int kOld = 16, kFields = 6;
  const size_t oldVertices = kOld * kOld;
  std::vector<double> values(2 * kFields * oldVertices, 0.0);
  std::vector<double> expected(size_t(kFields) * 40 * 40, 0.0);  // per field, the dense grid
  auto put = [&](size_t slot, int ti, int tk, int fl, int row, int col, double value) {
    values[(slot * kFields + size_t(fl)) * oldVertices + size_t(row * kOld + col)] = value;
    const int i = ti * kOld + col, k = tk * kOld + row;
    if (i < 40 && k < 40) expected[size_t(fl) * 1600 + size_t(k) * 40 + size_t(i)] = value;
  };
  for (int fl = 0; fl < kFields; ++fl)
    for (int row = 8; row < 16; ++row)
      for (int col = 0; col < 8; ++col) put(0, 1, 1, fl, row, col, 1.0 + fl + 0.01 * (row * kOld + col));
  for (int fl = 0; fl < kFields; ++fl)
    for (int row = 0; row < 8; ++row)
      for (int col = 0; col < 8; ++col) put(1, 2, 2, fl, row, col, 2.0 + fl + 0.01 * (row * kOld + col));
  FlowRecord r;
  r.restore(40, 40, 3.0, {4, 8}, values, kOld);
  CHECK(r.time() == 3.0);
  // Tile 4's quarter, then tile 8's one quarter inside the grid: (x 16, z 24) and (x 32, z 32).
  CHECK(r.tiles() == std::vector<int>{3 * 5 + 2, 4 * 5 + 4});
  const std::vector<std::vector<double>> dense = {r.wetTime(), r.flow(), r.flowX(), r.flowZ(), r.shearIntegral(),
                                                  r.shearPeak()};
  for (int fl = 0; fl < kFields; ++fl)
    CHECK(dense[size_t(fl)] == std::vector<double>(expected.begin() + fl * 1600, expected.begin() + (fl + 1) * 1600));
  // A tile of 16 beyond the grid, or values that do not fill whole tiles of 16, are refused.
  CHECK_THROWS_WITH(r.restore(40, 40, 1.0, {9}, std::vector<double>(kFields * oldVertices, 0.0), kOld),
                    "state is corrupt (flow maps)");
  CHECK_THROWS_WITH(r.restore(40, 40, 1.0, {0}, std::vector<double>(kFields * 64, 0.0), kOld),
                    "state is corrupt (flow maps)");
  CHECK(r.time() == 3.0);
}
