// Effects on demand: a pass whose effect the scene leaves out is never run (its call counter
// stays at zero), and the sediment-only scene runs without any fluid pass.
#include <catch2/catch.hpp>

#include "scene/presets.h"

using namespace scour;

namespace {
long calls(const World& w, Pass p) { return w.passCalls()[size_t(p)]; }

World stepped(SceneSpec spec, int steps) {
  Scene s = buildScene(spec);
  World w(s.desc);
  for (int k = 0; k < steps; ++k) w.step();
  return w;
}
}  // namespace

TEST_CASE("passes of effects that are off never run", "[effects]") {
  const SceneSpec river = presetSpec("valley", 0.2);
  const int n = 20;
  {
    const World w = stepped(river, n);  // everything on: every pass runs
    for (Pass p : {Pass::kSources, Pass::kSinks, Pass::kNoSlip, Pass::kSediment, Pass::kErosion,
                   Pass::kTerrain, Pass::kBoundaryParticles, Pass::kBoundaryNeighbors})
      CHECK(calls(w, p) > 0);
  }
  {
    SceneSpec s = river;
    s.effects.erosion = false;
    const World w = stepped(s, n);
    CHECK(calls(w, Pass::kErosion) == 0);
    CHECK(calls(w, Pass::kSediment) == n);  // settling, diffusion, deposition still on
  }
  {
    SceneSpec s = river;
    s.effects.erosion = s.effects.deposition = s.effects.settling = s.effects.diffusion = false;
    s.effects.no_slip = false;
    const World w = stepped(s, n);
    for (Pass p : {Pass::kSediment, Pass::kErosion, Pass::kTerrain, Pass::kNoSlip,
                   Pass::kBoundaryParticles, Pass::kBoundaryNeighbors})
      CHECK(calls(w, p) == 0);
    CHECK(w.boundary().size() == 0);  // no boundary particle was ever made
    CHECK(w.heightChange() == std::vector<double>(w.heightChange().size(), 0.0));
  }
  {
    SceneSpec s = river;
    s.effects.sources = s.effects.sinks = false;
    const World w = stepped(s, n);
    CHECK(calls(w, Pass::kSources) == 0);
    CHECK(calls(w, Pass::kSinks) == 0);
    CHECK(w.emitted() == 0);
  }
  {
    SceneSpec s = presetSpec("rain", 0.5);
    const World on = stepped(s, n);
    CHECK(calls(on, Pass::kRain) == n);
    CHECK(on.emitted() > 0);
    s.effects.rain = false;
    const World off = stepped(s, n);
    CHECK(calls(off, Pass::kRain) == 0);
    CHECK(off.emitted() == 0);
  }
}

TEST_CASE("surface tension is computed only when the effect is on", "[effects]") {
  SceneSpec s = presetSpec("hydrostatic", 0.1);
  s.params.surface_tension = 0.5;
  s.effects.surface_tension = false;
  const World off = stepped(s, 3);
  s.params.surface_tension = 0.0;
  const World none = stepped(s, 3);
  CHECK(off.stateHash() == none.stateHash());  // κ is set, but the effect is off
  s.params.surface_tension = 0.5;
  s.effects.surface_tension = true;
  CHECK(stepped(s, 3).stateHash() != none.stateHash());
}

TEST_CASE("the sediment-only scene runs without the fluid passes", "[effects]") {
  const SceneSpec s = presetSpec("settling");
  REQUIRE_FALSE(s.effects.fluid_motion);
  Scene scene = buildScene(s);
  World w(scene.desc);
  const std::vector<Vec3f> x0 = w.fluid().x;
  for (int k = 0; k < 30; ++k) w.step();
  for (Pass p : {Pass::kDensity, Pass::kForces, Pass::kBoundaryForces, Pass::kIntegrate, Pass::kNoSlip})
    CHECK(calls(w, p) == 0);
  CHECK(calls(w, Pass::kNeighborSearch) == 1);  // once, at the start: the lattice never moves
  CHECK(calls(w, Pass::kSediment) == 30);
  CHECK(w.fluid().x == x0);
}

TEST_CASE("live edits: parameters, sources, sinks and the water brush", "[effects][edits]") {
  Scene s = makePreset("valley", 0.2);
  World w(s.desc);
  w.step();
  // Parameters: a valid change applies; the particle-shaping ones are refused.
  SimParams p = w.params();
  p.k_eps = 0.3;
  w.setParams(p);
  CHECK(w.params().k_eps == 0.3);
  // The study's sediment forms switch live (the next step uses them); the neighbor search needs
  // a reset.
  p.advection = SettlingAdvection::kNaiveGradient;
  p.diffusion_form = DiffusionForm::kPrinted;
  w.setParams(p);
  CHECK(w.params().advection == SettlingAdvection::kNaiveGradient);
  CHECK(w.params().diffusion_form == DiffusionForm::kPrinted);
  w.step();
  CHECK(w.soilBudget().relativeError() < World::kSoilTolerance);  // the leak is counted
  p.advection = SettlingAdvection::kDonorAcceptor;
  p.diffusion_form = DiffusionForm::kConsistent;
  w.setParams(p);
  p.neighbor_search = NeighborSearch::kKdTree;
  CHECK_THROWS_WITH(w.setParams(p), Catch::Contains("engine.neighbor_search"));
  CHECK(w.params().neighbor_search == NeighborSearch::kGrid);
  p.neighbor_search = NeighborSearch::kGrid;
  p.spacing *= 2;
  CHECK_THROWS_WITH(w.setParams(p), Catch::Contains("fluid.spacing"));
  CHECK(w.params().spacing == s.spec.params.spacing);
  // Sources and sinks.
  const size_t n0 = w.sources().size();
  Source src;
  src.center = {1.0, 0.6, 0.4};
  src.radius = 0.04;
  src.rate = 0.001;
  CHECK(w.addSource(src) == n0);
  src.rate = -1;
  CHECK_THROWS_WITH(w.updateSource(n0, src), Catch::Contains("rate must be positive"));
  w.removeSource(n0);
  CHECK(w.sources().size() == n0);
  CHECK_THROWS(w.removeSource(99));
  const size_t sinks = w.sinks().size();
  CHECK(w.addSink({{0, -1, 0}, {0.1, 2, 0.8}}) == sinks);
  CHECK(w.sinks().size() == sinks + 1);
  // The brush: water at rest on the lattice, above the terrain, a full Δs from other water;
  // painting the same place again adds nothing.
  const size_t before = w.fluid().size();
  const long added = w.addWater({1.0, 0.45, 0.4}, 0.06);
  CHECK(added > 0);
  CHECK(long(w.fluid().size() - before) == added);
  const double ds = w.params().spacing;
  for (size_t i = before; i < w.fluid().size(); ++i) {
    const Vec3f& x = w.fluid().x[i];
    CHECK(x.y() >= w.terrain().heightAt(x.x(), x.z()) + 0.5 * ds - 1e-6);
    for (size_t j = 0; j < w.fluid().size(); ++j)
      if (j != i) REQUIRE((w.fluid().x[j] - x).norm() >= 0.95 * ds - 1e-6);
  }
  CHECK(w.addWater({1.0, 0.45, 0.4}, 0.06) == 0);
  CHECK(w.painted() == added);
  for (int k = 0; k < 50; ++k) w.step();  // and the run goes on within its invariants
}
