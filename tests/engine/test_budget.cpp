// The soil budget closes: terrain + suspended + removed stays constant to 1e-6 relative in a river
// that erodes, carries, settles, deposits and loses water through a sink, and C stays in
// [0, C_max] in every particle at every step; also when erosion is pushed into saturation.
#include <catch2/catch.hpp>

#include "scene/presets.h"

using namespace scour;

namespace {
struct Worst {
  double budget = 0, cmin = 1e300, cmax = -1e300;
};
Worst runChecked(World& w, int steps) {
  Worst r;
  for (int k = 0; k < steps; ++k) {
    w.step();
    r.budget = std::max(r.budget, w.soilBudget().relativeError());
    for (size_t i = 0; i < w.fluid().size(); ++i) {
      r.cmin = std::min(r.cmin, w.concentration(i));
      r.cmax = std::max(r.cmax, w.concentration(i));
    }
  }
  return r;
}
}  // namespace

TEST_CASE("a river closes the soil budget over 2,000 steps", "[budget][erosion]") {
  Scene s = makePreset("valley", 0.5);
  REQUIRE(s.desc.effects.erosion);
  REQUIRE(s.desc.effects.deposition);
  REQUIRE(s.desc.effects.settling);
  REQUIRE(s.desc.effects.diffusion);
  World w(s.desc);
  Worst r = runChecked(w, 2000);
  const SoilBudget b = w.soilBudget();
  INFO("terrain " << b.terrain << " suspended " << b.suspended << " removed " << b.removed
                  << " initial " << b.initial << "; worst relative error " << r.budget);
  CHECK(r.budget < 1e-6);
  CHECK(r.cmin >= 0.0);
  CHECK(r.cmax <= w.params().c_max * (1 + 1e-12));
  // The river did work: soil left the terrain, some is in the water, some went out the sink,
  // and some was laid down again.
  CHECK(b.terrain < b.initial);
  CHECK(b.suspended > 0.0);
  CHECK(b.removed > 0.0);
  double deposited = 0;
  for (double d : w.heightChange()) deposited = std::max(deposited, d);
  CHECK(deposited > 0.0);
  WARN("river: worst budget error " << r.budget << ", eroded " << b.initial - b.terrain << " m³");
}

TEST_CASE("saturation: C never passes C_max and soil is still conserved", "[budget][erosion]") {
  Scene s = makePreset("valley", 0.25);
  s.desc.params.k_eps = 1000.0;  // 10,000× the paper's: every contact wants to fill its particle
  s.desc.params.c_max = 0.05;
  World w(s.desc);
  Worst r = runChecked(w, 600);
  CHECK(r.budget < 1e-6);
  CHECK(r.cmin >= 0.0);
  CHECK(r.cmax <= 0.05 * (1 + 1e-12));  // C = s/V with s ≤ C_max·V: rounding only
  CHECK(r.cmax > 0.05 * (1 - 1e-9));     // saturation was reached
}
