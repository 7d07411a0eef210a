// The erosion maps (engine/maps.h, issue 17) agree with the soil ledger: Σ wear × vertex area is
// the eroded volume, Σ deposition × area the deposited volume, Σ sediment × area the suspended
// volume, each to 1e-9 relative; every value is ≥ 0, and a vertex is never both worn and built.
#include <catch2/catch.hpp>

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
  // The deepest cut is the wear map's peak.
  double peak = 0;
  for (double v : maps[0].values) peak = std::max(peak, v);
  CHECK(peak == change.max_erosion);
}
