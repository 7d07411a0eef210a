// The geologic clock (model.md, "two clocks"): the bed takes N times each step's net exchange, the
// bed's time is ∫ N dt, the soil ledger (terrain + suspended + removed − what the factor added)
// closes to rounding at any N, across a change of N and a resume, and the bed guard lowers N
// where the bed would move too fast.
#include <catch2/catch.hpp>
#include <omp.h>

#include <sstream>

#include "scene/presets.h"

using namespace scour;

namespace {

Scene river(double factor, double spinup = 0.0, double bound = 1.0) {
  SceneSpec spec = presetSpec("valley", 0.3);
  spec.params.morphological_factor = factor;
  spec.params.morphological_spinup = spinup;
  spec.params.max_bed_step = bound;
  return buildScene(spec);
}

// Steps w, checking the ledger after every step; returns the worst relative error.
double stepChecked(World& w, int steps) {
  double worst = 0;
  for (int k = 0; k < steps; ++k) {
    w.step();
    worst = std::max(worst, w.soilBudget().relativeError());
  }
  return worst;
}

}  // namespace

TEST_CASE("at N = 1 the bed's clock is the water's and the factor adds nothing", "[clock][budget]") {
  Scene s = river(1.0);
  REQUIRE(s.desc.effects.erosion);
  World w(s.desc);
  CHECK(stepChecked(w, 60) < 1e-12);
  CHECK(w.morphologicalTime() == w.time());
  CHECK(w.soilBudget().morphological == 0.0);
  CHECK(w.bedGuard().lowered == 0);
}

TEST_CASE("at N = 100 the bed takes 100 times the water's exchange and the ledger closes", "[clock][budget]") {
  const double n = 100;
  Scene s = river(n);
  World w(s.desc);
  const SoilBudget start = w.soilBudget();
  REQUIRE(start.suspended == 0.0);
  const double worst = stepChecked(w, 150);
  const SoilBudget b = w.soilBudget();
  INFO("terrain " << b.terrain << ", suspended " << b.suspended << ", removed " << b.removed
                  << ", added by the factor " << b.morphological << "; worst error " << worst);
  CHECK(worst < 1e-12);
  // All the soil in the water came from the bed: the bed lost N times as much.
  const double taken = b.suspended + b.removed;
  REQUIRE(taken > 0);
  CHECK(start.terrain - b.terrain == Approx(n * taken).epsilon(1e-9));
  CHECK(b.morphological == Approx(-(n - 1) * taken).epsilon(1e-9));
  CHECK(w.morphologicalTime() == Approx(n * w.time()).epsilon(1e-12));
  CHECK(w.bedGuard().lowered == 0);
}

TEST_CASE("the speed-up waits for its spin-up, and the bed's clock is the sum of N dt", "[clock]") {
  const double n = 10, spinup = 0.02;
  Scene s = river(n, spinup);
  World w(s.desc);
  double expected = 0;
  int slow = 0, fast = 0;
  for (int k = 0; k < 40; ++k) {
    const StepStats st = w.step();
    const bool spun = st.time - st.dt >= spinup;
    CHECK(st.factor == (spun ? n : 1.0));
    (spun ? fast : slow) += 1;
    expected += st.factor * st.dt;
    CHECK(st.morph_time == expected);
  }
  CHECK(slow > 0);
  CHECK(fast > 0);
  CHECK(w.morphologicalTime() == expected);
}

TEST_CASE("a change of N mid-run and a resume keep the ledger closed, and the resume is bit for bit",
          "[clock][budget][checkpoint]") {
  Scene s = river(1.0);
  World w(s.desc);
  CHECK(stepChecked(w, 40) < 1e-12);
  SimParams p = w.params();
  p.morphological_factor = 50;
  w.setParams(p);
  CHECK(w.morphologicalFactor() == 50);
  CHECK(stepChecked(w, 40) < 1e-12);
  CHECK(w.soilBudget().morphological != 0.0);
  std::stringstream state;
  w.saveState(state);
  // The resumed world is built from the scene as it is now (the checkpoint records the edit).
  Scene now = river(50);
  World resumed(now.desc);
  resumed.loadState(state);
  CHECK(resumed.morphologicalTime() == w.morphologicalTime());
  CHECK(resumed.morphologicalFactor() == 50);
  CHECK(resumed.soilBudget().morphological == w.soilBudget().morphological);
  // A world whose user has asked for another speed-up since (a snapshot restored after the
  // slider moved) takes the state and runs at what was asked for.
  {
    std::stringstream again(state.str());
    World faster(river(1000).desc);
    faster.loadState(again);
    CHECK(faster.morphologicalFactor() == 1000);
    CHECK(faster.morphologicalTime() == w.morphologicalTime());
  }
  CHECK(resumed.soilBudget().relativeError() == w.soilBudget().relativeError());
  for (int k = 0; k < 25; ++k) w.step(), resumed.step();
  CHECK(resumed.stateHash() == w.stateHash());
  CHECK(resumed.morphologicalTime() == w.morphologicalTime());
  CHECK(resumed.soilBudget().relativeError() < 1e-12);
  // Back to 1: the ledger keeps what the factor added and still closes.
  p.morphological_factor = 1;
  w.setParams(p);
  const double added = w.soilBudget().morphological;
  CHECK(stepChecked(w, 20) < 1e-12);
  CHECK(w.soilBudget().morphological == added);
}

TEST_CASE("the bed guard halves N until no step moves the bed more than its bound", "[clock]") {
  // N = 10⁴ on a river that cuts about 1e-6 Δs a step: 10⁻² Δs a step, a hundred times the
  // bound of 10⁻⁴ Δs.
  const double n = 1e4, bound = 1e-4;
  Scene s = river(n, 0.0, bound);
  World w(s.desc);
  double worst = 0;
  for (int k = 0; k < 80; ++k) {
    const StepStats st = w.step();
    if (st.factor > 1) CHECK(st.bed_step_ds <= bound * (1 + 1e-12));
    CHECK(st.bed_fast_fraction >= 0.0);
    CHECK(st.bed_fast_fraction <= 1.0);
    worst = std::max(worst, w.soilBudget().relativeError());
  }
  const Ledger::BedGuard& g = w.bedGuard();
  INFO("lowered " << g.lowered << " times, to " << g.lowest << "; now " << w.morphologicalFactor());
  CHECK(g.lowered >= 1);
  CHECK(w.morphologicalFactor() < n);
  CHECK(g.lowest == w.morphologicalFactor());
  CHECK(g.lastFrom > g.lowest);
  CHECK(worst < 1e-12);
  // Setting the parameter again is the user's word: the factor is theirs until the guard acts.
  SimParams p = w.params();
  p.morphological_factor = 20;
  w.setParams(p);
  CHECK(w.morphologicalFactor() == 20);
}

TEST_CASE("under DFSPH the guard's bound is per WCSPH step of water, so N is the same under either solver",
          "[clock][dfsph]") {
  // The bound is the bed's speed against the water: a DFSPH step k = Δt / (λ h / c_s) times as long
  // as WCSPH's may move the bed k times as far. Same river, same N and bound as above.
  const double n = 1e4, bound = 1e-4;
  Scene s = river(n, 0.0, bound);
  s.desc.params.solver = FluidSolver::kDfsph;
  World df(s.desc);
  const SimParams& p = df.params();
  const double wcsphStep = p.cfl * p.support() / p.sound_speed;
  bool beyondPlain = false;
  for (int k = 0; k < 40; ++k) {
    const StepStats st = df.step();
    const double allowed = bound * std::max(1.0, st.dt / wcsphStep);
    if (st.factor > 1) CHECK(st.bed_step_ds <= allowed * (1 + 1e-12));
    beyondPlain = beyondPlain || st.bed_step_ds > bound;
  }
  CHECK(beyondPlain);  // the longer steps used the room they were given
  World wc(river(n, 0.0, bound).desc);
  while (wc.time() < df.time()) wc.step();
  INFO("over " << df.time() << " s of water: N = " << df.morphologicalFactor() << " under DFSPH, "
               << wc.morphologicalFactor() << " under WCSPH");
  CHECK(df.bedGuard().lowered >= 1);
  CHECK(df.morphologicalFactor() >= 0.5 * wc.morphologicalFactor());
  CHECK(df.morphologicalFactor() <= 2.0 * wc.morphologicalFactor());
  CHECK(df.soilBudget().relativeError() < 1e-12);
}

// erosion.exchange_every = K (model.md, "the bed's work every K steps"): the bed and the water's
// sediment change only on every K-th step, by the K steps' exchange; the ledger closes at every
// step, at N = 1 and N = 100 alike, and the run is the same at 1 and 2 threads and across a resume.
TEST_CASE("with the bed's work every 4 steps the terrain moves only on those steps and the ledger closes",
          "[clock][budget][determinism]") {
  constexpr int kEvery = 4;
  auto make = [&](double n) {
    SceneSpec spec = presetSpec("valley", 0.3);
    spec.params.morphological_factor = n;
    spec.params.max_bed_step = 1.0;
    spec.params.exchange_every = kEvery;
    return std::make_unique<World>(buildScene(spec).desc);
  };
  for (double n : {1.0, 100.0}) {
    INFO("N = " << n);
    std::unique_ptr<World> w = make(n);
    int moved = 0;
    double worst = 0;
    for (int k = 0; k < 120; ++k) {
      const double terrain = w->soilBudget().terrain;
      w->step();
      worst = std::max(worst, w->soilBudget().relativeError());
      if (w->steps() % kEvery != 0) REQUIRE(w->soilBudget().terrain == terrain);
      else moved += w->soilBudget().terrain != terrain;
    }
    CHECK(worst < 1e-12);
    CHECK(moved > 10);
    CHECK(w->passCalls()[size_t(Pass::kErosion)] == 120 / kEvery);
    CHECK(w->passCalls()[size_t(Pass::kFlowMaps)] == 120 / kEvery);
    CHECK(w->soilBudget().suspended > 0.0);
    if (n > 1) CHECK(w->soilBudget().morphological != 0.0);
  }
  // 1 and 2 threads, and a resume from step 50 (between two exchanges), bit for bit.
  auto hash = [&](int threads, int steps) {
    omp_set_num_threads(threads);
    std::unique_ptr<World> w = make(100.0);
    for (int k = 0; k < steps; ++k) w->step();
    return w->stateHash();
  };
  const uint64_t two = hash(2, 90);
  CHECK(hash(1, 90) == two);
  std::unique_ptr<World> first = make(100.0);
  for (int k = 0; k < 50; ++k) first->step();
  std::stringstream state;
  first->saveState(state);
  std::unique_ptr<World> resumed = make(100.0);
  resumed->loadState(state);
  for (int k = 0; k < 40; ++k) resumed->step();
  CHECK(resumed->stateHash() == two);
  omp_set_num_threads(omp_get_num_procs());
}
