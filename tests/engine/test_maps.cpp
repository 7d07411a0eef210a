// The erosion maps (engine/maps.h, issue 17) agree with the soil ledger: Σ wear × vertex area is
// the eroded volume, Σ deposition × area the deposited volume, Σ sediment × area the suspended
// volume, each to 1e-9 relative; every value is ≥ 0, and a vertex is never both worn and built.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "engine/maps.h"
#include "engine/sediment.h"
#include "scene/presets.h"

using namespace scour;

TEST_CASE("the erosion maps sum to the ledger's volumes", "[maps][budget]") {
  // The valley river at N = 20 after a short spin-up: both erosion and deposition under way.
  SceneSpec spec = presetSpec("valley", 0.3);
  spec.params.morphological_factor = 20;
  spec.params.morphological_spinup = 0.02;
  World w(buildScene(spec).desc);
  for (int k = 0; k < 250; ++k) w.step();
  const std::vector<TerrainMap> maps = erosionMaps(w);
  REQUIRE(maps.size() == 3);
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
