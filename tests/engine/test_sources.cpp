// Sources emit their flow rate without overlapping particles; sinks and open walls remove
// particles and count them; the pass counters show that absent effects never run.
#include <catch2/catch.hpp>

#include "scene/presets.h"

using namespace scour;

namespace {
Scene emptyBox() {
  Scene s;
  s.desc.params.spacing = 0.02;
  s.desc.params.sound_speed = 20;
  s.desc.terrain = Heightfield(41, 41, 0.025, 0.025);  // 1 m × 1 m, flat
  return s;
}
}  // namespace

TEST_CASE("a source emits Q·t without overlap", "[sources]") {
  Scene s = emptyBox();
  Source src;
  src.center = {0.5, 0.6, 0.5};
  src.radius = 0.05;
  src.direction = {0, -1, 0};
  src.rate = 0.0004;  // m³/s
  s.desc.sources.push_back(src);
  World w(s.desc);
  while (w.time() < 0.2) w.step();
  const double ds = s.desc.params.spacing;
  const double volume = double(w.emitted()) * ds * ds * ds;
  // One layer of the disk is the granularity.
  int slots = 0;
  for (int b = -3; b <= 3; ++b)
    for (int a = -3; a <= 3; ++a) slots += (a * a + b * b) * ds * ds <= src.radius * src.radius + 1e-12;
  INFO("emitted " << w.emitted() << " particles = " << volume << " m³; Q t = " << src.rate * w.time());
  CHECK(std::abs(volume - src.rate * w.time()) <= slots * ds * ds * ds + 1e-12);
  CHECK(w.blockedSlots() == 0);
  // No two particles closer than 0.9 Δs right after emission.
  const Fluid& f = w.fluid();
  float closest = 1e9f;
  for (size_t i = 0; i < f.size(); ++i)
    for (size_t j = i + 1; j < f.size(); ++j) closest = std::min(closest, (f.x[i] - f.x[j]).norm());
  CHECK(closest > 0.9 * ds);
  CHECK(w.passCalls()[size_t(Pass::kSources)] == w.steps());
  CHECK(w.passCalls()[size_t(Pass::kSinks)] == 0);       // no sink, closed walls
  CHECK(w.passCalls()[size_t(Pass::kNoSlip)] == 0);      // effect off
  CHECK(w.passCalls()[size_t(Pass::kBoundaryParticles)] == 0);
}

TEST_CASE("sinks and open walls remove particles and count them", "[sources]") {
  Scene s = makePreset("dambreak", 0.3);
  const size_t n0 = s.desc.particles.size();
  SECTION("open domain") {
    s.desc.domain.walls = false;
    World w(s.desc);
    while (w.time() < 0.5) w.step();
    CHECK(w.removedByOutflow() > 0);
    CHECK(w.fluid().size() + size_t(w.removedByOutflow()) == n0);
    for (const auto& x : w.fluid().x) REQUIRE(x.x() <= w.terrain().xMax());
  }
  SECTION("a sink at the far end") {
    const Heightfield& hf = s.desc.terrain;
    Sink k;
    k.lo = {hf.xMax() - 0.1, -1, -1};
    k.hi = {hf.xMax() + 1, 1, 1};
    s.desc.sinks.push_back(k);
    World w(s.desc);
    while (w.time() < 0.5) w.step();
    CHECK(w.removedBySinks() > 0);
    CHECK(w.fluid().size() + size_t(w.removedBySinks()) == n0);
    for (const auto& x : w.fluid().x) REQUIRE_FALSE(k.contains(x));
  }
}
