// Water sliding down an inclined valley for 2,000 steps: no fluid particle ever gets deeper than
// 0.5 Δs below the terrain (the World stops with InvariantViolation if one does), none leaves the
// closed domain, and the water actually moved (so the test exercises the boundary).
#include <catch2/catch.hpp>

#include "scene/presets.h"

using namespace scour;

TEST_CASE("no particle penetrates the terrain on a slope", "[physics][boundary]") {
  Scene s = makePreset("slope");
  World w(s.desc);
  double x0 = 0;
  for (const auto& x : w.fluid().x) x0 += x.x();
  x0 /= double(w.fluid().size());
  for (int k = 0; k < 2000; ++k) REQUIRE_NOTHROW(w.step());
  const auto& inv = w.invariants();
  CHECK(inv.max_penetration_over_ds <= 0.5);
  CHECK(inv.nan == 0);
  CHECK(inv.escaped == 0);
  double x1 = 0, deepest = -1e9;
  for (const auto& x : w.fluid().x) {
    x1 += x.x();
    deepest = std::max(deepest, (w.terrain().heightAt(x.x(), x.z()) - x.y()) / s.desc.params.spacing);
  }
  x1 /= double(w.fluid().size());
  INFO("mean x moved from " << x0 << " to " << x1 << " m; deepest now " << deepest << " Δs");
  CHECK(x1 - x0 > 0.2);
  CHECK(deepest <= 0.5);
  WARN("slope: max penetration over the run = " << inv.max_penetration_over_ds << " Δs");
}

TEST_CASE("a violated invariant stops the run with a message naming step and particle",
          "[invariants]") {
  Scene s = makePreset("slope");
  // Gravity 50× and a penalty far too soft to hold it: particles fall through the terrain.
  s.desc.params.gravity = 100.0;
  s.desc.params.penalty_stiffness = 1.0;
  s.desc.params.penalty_damping = 1.0;
  World w(s.desc);
  std::string message;
  try {
    for (int k = 0; k < 5000; ++k) w.step();
  } catch (const InvariantViolation& e) {
    message = e.what();
  }
  REQUIRE_FALSE(message.empty());
  // Whichever it meets first, a particle deep in the terrain or one through a wall.
  CHECK_THAT(message, Catch::Contains("step ") && Catch::Contains("particle ") &&
                          (Catch::Contains("below the terrain") ||
                           Catch::Contains("left the domain through a closed wall")));
}
