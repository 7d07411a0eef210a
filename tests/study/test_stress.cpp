// The stress runner's own checks: they must catch a blow-up, and the energy ledger must account
// for what sources bring in.
#include <catch2/catch.hpp>

#include <sstream>

#include "study/stress.h"

using namespace scour;

TEST_CASE("stress: a step far beyond the CFL limit is caught as an energy blow-up", "[stress]") {
  StressScene s = stressScene("dambreak-wall");
  s.spec.params.fixed_dt = 0.004;  // 16× the CFL step of this scene
  s.spec.stress.duration = 0.3;
  const StressResult r = runStress(s);
  REQUIRE_FALSE(r.pass);
  CHECK(!r.failure.empty());
  CHECK(r.steps < 75);  // caught at the step it happened, not at the end
}

TEST_CASE("stress: the ledger counts a source's energy, so a jet's energy stays bounded",
          "[stress]") {
  StressScene s = stressScene("waterfall-drop");
  s.spec.stress.duration = 0.25;
  const StressResult r = runStress(s);
  REQUIRE(r.pass);
  CHECK(r.emitted > 100);  // the jet brought particles (and their energy) in
  CHECK(r.lost == 0);
  // Falling 1 m the jet turns potential energy into kinetic: bounded, not created.
  CHECK(r.energy_excess <= 0.01);
}

TEST_CASE("stress: nothing is placed inside a closed wall's contact zone", "[stress]") {
  StressScene s = stressScene("edge-source");
  s.spec.stress.duration = 0.1;
  const Scene built = buildScene(s.spec);
  World w(built.desc);
  // Right after a step, the particles it emitted stand where they were placed (emission follows
  // the drift): none of them within Δs/2 of a wall.
  const double margin = 0.5 * w.params().spacing;
  uint32_t seen = 0;
  long fresh = 0;
  for (int k = 0; k < 100; ++k) {
    w.step();
    const Fluid& f = w.fluid();
    uint32_t top = seen;
    for (size_t i = 0; i < f.size(); ++i) {
      if (f.id[i] < seen) continue;
      ++fresh;
      top = std::max(top, f.id[i] + 1);
      CHECK(f.x[i].x() >= w.terrain().x0() + margin * (1 - 1e-5));
      CHECK(f.x[i].z() >= w.terrain().z0() + margin * (1 - 1e-5));
    }
    seen = top;
  }
  CHECK(fresh == w.emitted());
  CHECK(w.blockedSlots() > 0);  // the slots nearer the walls were refused
}

TEST_CASE("stress: an unknown scene is refused with the valid names", "[stress]") {
  REQUIRE_THROWS_WITH(stressScene("nope"),
                      Catch::Contains("unknown stress scene 'nope'") && Catch::Contains("cliffs"));
}

TEST_CASE("stress: a run resumed while the density-rate bound limits Δt steps on bit for bit",
          "[stress][checkpoint]") {
  const StressScene s = stressScene("dambreak-wall");
  const WorldDesc desc = buildScene(s.spec).desc;
  World a(desc);
  const SimParams& p = a.params();
  const double acoustic = p.cfl * p.support() / p.sound_speed;  // the CFL bound at rest
  // Run into the surge until the density rate is what limits the next step.
  while (!(a.densityRate() > 0 && p.density_cfl / a.densityRate() < acoustic)) {
    a.step();
    REQUIRE(a.time() < 1.0);
  }
  std::stringstream state;
  a.saveState(state);
  World b(desc);
  b.loadState(state);
  REQUIRE(b.densityRate() == a.densityRate());
  for (int k = 0; k < 50; ++k) {
    a.step();
    b.step();
    REQUIRE(b.lastDt() == a.lastDt());
  }
  CHECK(b.stateHash() == a.stateHash());
}

TEST_CASE("stress: the energy ledger follows a change of gravity", "[stress]") {
  const StressScene s = stressScene("deep-column");
  World w(buildScene(s.spec).desc);
  // At rest the ledger is the potential energy; with g doubled it must be again.
  REQUIRE(std::abs(w.energyLedger() - w.mechanicalEnergy()) <= 1e-9 * w.mechanicalEnergy());
  SimParams p = w.params();
  p.gravity *= 2;
  w.setParams(p);
  CHECK(std::abs(w.energyLedger() - w.mechanicalEnergy()) <= 1e-9 * w.mechanicalEnergy());
}

TEST_CASE("stress: rain falls clear of closed walls' contact zone", "[stress]") {
  StressScene s = stressScene("cloudburst");  // rain over the whole walled crater
  World w(buildScene(s.spec).desc);
  const double margin = w.params().spacing * std::max(0.5, w.params().contact_over_spacing);
  uint32_t seen = 0;
  for (int k = 0; k < 150; ++k) {
    w.step();
    const Fluid& f = w.fluid();
    uint32_t top = seen;
    for (size_t i = 0; i < f.size(); ++i) {
      if (f.id[i] < seen) continue;
      top = std::max(top, f.id[i] + 1);
      const Vec3f& x = f.x[i];
      CHECK(x.x() >= w.terrain().x0() + margin * (1 - 1e-3));
      CHECK(x.x() <= w.terrain().xMax() - margin * (1 - 1e-3));
      CHECK(x.z() >= w.terrain().z0() + margin * (1 - 1e-3));
      CHECK(x.z() <= w.terrain().zMax() - margin * (1 - 1e-3));
    }
    seen = top;
  }
  CHECK(w.emitted() > 50);  // about 1,300 drops a second: the checks above saw many
}
