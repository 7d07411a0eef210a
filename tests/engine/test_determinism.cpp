// The same scene gives a bit-identical state at 1 and 2 OpenMP threads: sources, sinks, no-slip
// friction, Z-order reordering, the boundary tiles, erosion, settling, diffusion and deposition
// all run in the default scene.
#include <catch2/catch.hpp>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <sstream>

#include "engine/parallel.h"
#include "engine/sediment.h"
#include "scene/presets.h"

using namespace scour;

namespace {
uint64_t hashAfter(const std::string& preset, int threads, int steps) {
  omp_set_num_threads(threads);
  Scene s = makePreset(preset, 0.3);
  World w(s.desc);
  for (int k = 0; k < steps; ++k) w.step();
  if (s.desc.effects.erosion) {
    // The hash covers erosion at work: sediment in the water, the terrain moved.
    REQUIRE(w.soilBudget().suspended > 0.0);
  }
  return w.stateHash();
}
}  // namespace

TEST_CASE("state hash is identical at 1 and 2 threads", "[determinism]") {
  for (const char* preset : {"valley", "dambreak"}) {
    INFO(preset);
    uint64_t one = hashAfter(preset, 1, 400);
    uint64_t two = hashAfter(preset, 2, 400);
    CHECK(one == two);
    CHECK(one != hashAfter(preset, 2, 399));  // the hash does see the state
  }
  omp_set_num_threads(omp_get_num_procs());
}

TEST_CASE("above kParallelFrom the light loops run in parallel and give the bits of one thread",
          "[determinism]") {
  // Below kParallelFrom elements the light loops (engine/parallel.h) run on the calling thread at
  // any thread count, so the small scenes above never take their parallel path: canyon 0.5 holds
  // more fluid and more boundary particles than that, with erosion, deposition and the flow
  // record at work.
  auto run = [](int threads) {
    omp_set_num_threads(threads);
    Scene s = makePreset("canyon", 0.5);
    s.desc.params.exchange_every = 1;
    World w(s.desc);
    REQUIRE(w.fluid().size() >= kParallelFrom);
    for (int k = 0; k < 12; ++k) w.step();
    REQUIRE(w.boundary().size() >= kParallelFrom);
    REQUIRE(w.soilBudget().suspended > 0.0);
    return std::make_pair(w.stateHash(), w.flowRecord().values());
  };
  const auto two = run(2);
  CHECK(run(1) == two);
  omp_set_num_threads(omp_get_num_procs());
}

TEST_CASE("spacing sampling: the canyon's soil budget closes, the same at 1 and 2 threads, and a "
          "resumed state steps on bit for bit", "[determinism][boundary]") {
  auto run = [](int threads, int steps, World** keep = nullptr) {
    omp_set_num_threads(threads);
    SceneSpec spec = presetSpec("canyon", 0.03);
    spec.params.boundary_sampling = BoundarySampling::kSpacing;
    Effects& fx = spec.effects;
    fx.erosion = fx.settling = fx.diffusion = fx.deposition = true;
    auto w = std::make_unique<World>(buildScene(spec).desc);
    for (int k = 0; k < steps; ++k) w->step();
    if (keep) *keep = w.release();
    return w ? w->stateHash() : (*keep)->stateHash();
  };
  World* a = nullptr;
  const uint64_t two = run(2, 150, &a);
  std::unique_ptr<World> owner(a);
  // Block particles at work: the terrain is finer than Δs, and soil moved.
  const BoundaryParticles& b = a->boundary();
  REQUIRE(std::count_if(b.patch.begin(), b.patch.end(), [](int p) { return p >= 0; }) > 0);
  const SoilBudget s = a->soilBudget();
  INFO("suspended " << s.suspended << ", error " << s.relativeError());
  CHECK(s.suspended > 0);
  CHECK(s.relativeError() < 1e-12);
  CHECK(run(1, 150) == two);
  // A saved state resumes onto the same steps, the volumes waiting for their triangles with it.
  REQUIRE(a->terrainWaiting() != 0.0);
  // Outputs show the settled terrain: the waiting volumes in its heights, exactly.
  const Heightfield settled = a->settledTerrain();
  const std::vector<double> areas = vertexAreas(settled);
  double settledVolume = 0;
  for (size_t v = 0; v < areas.size(); ++v) settledVolume += (settled.heights()[v] - a->terrain().heights()[v]) * areas[v];
  CHECK(settledVolume == Approx(a->terrainWaiting()).epsilon(1e-9));
  CHECK(a->heightChange()[0] == settled.heights()[0] - a->initialTerrain().heights()[0]);
  std::stringstream state;
  a->saveState(state);
  SceneSpec spec = presetSpec("canyon", 0.03);
  spec.params.boundary_sampling = BoundarySampling::kSpacing;
  Effects& fx = spec.effects;
  fx.erosion = fx.settling = fx.diffusion = fx.deposition = true;
  World resumed(buildScene(spec).desc);
  resumed.loadState(state);
  CHECK(resumed.terrainWaiting() == a->terrainWaiting());
  CHECK(resumed.soilBudget().terrain == a->soilBudget().terrain);
  for (int k = 0; k < 30; ++k) a->step(), resumed.step();
  CHECK(resumed.stateHash() == a->stateHash());
  CHECK(resumed.flowRecord().values() == a->flowRecord().values());
  // The waiting volumes come before the flow record (its time, tiles and values), and what each
  // of them is ends the state: (n, n triangles), (n, n volumes), the record, (n, n codes). A
  // volume that is not finite, a triangle outside the terrain or a code that is neither a
  // triangle's nor a block's inside the terrain is refused, and the world keeps its state.
  std::stringstream again;
  a->saveState(again);
  const std::string whole = again.str();
  auto u64In = [&](const std::string& s, size_t at) {
    uint64_t v = 0;
    std::memcpy(&v, s.data() + at, sizeof v);
    return v;
  };
  size_t codes = 0;
  while (codes + 8 < whole.size() && u64In(whole, whole.size() - codes - 8) != codes) ++codes;
  const size_t record = 8 + (8 + 4 * a->flowRecord().tiles().size()) + (8 + 8 * a->flowRecord().values().size()) + 8 + codes;
  const std::string bytes = whole.substr(0, whole.size() - record), flow = whole.substr(whole.size() - record);
  auto u64At = [&](size_t at) { return u64In(bytes, at); };
  size_t n = 1;
  while (n < bytes.size() / 12 && !(u64At(bytes.size() - 8 * n - 8) == n && u64At(bytes.size() - 12 * n - 16) == n)) ++n;
  REQUIRE(u64At(bytes.size() - 8 * n - 8) == n);
  auto refuse = [&](const std::string& damaged) {
    std::stringstream in(damaged + flow);
    const uint64_t before = resumed.stateHash();
    try {
      resumed.loadState(in);
    } catch (const std::runtime_error& e) {
      CHECK(resumed.stateHash() == before);
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  std::string nan = bytes;
  const double bad = std::nan("");
  std::memcpy(nan.data() + nan.size() - sizeof(double), &bad, sizeof bad);
  CHECK(refuse(nan) == "state is corrupt (waiting terrain volumes)");
  std::string outside = bytes;
  const int32_t nowhere = -1;
  std::memcpy(outside.data() + outside.size() - 12 * n - 8, &nowhere, sizeof nowhere);
  CHECK(refuse(outside) == "state is corrupt (waiting terrain volumes)");
  REQUIRE(codes == n);
  // Blocks' banks wait, and resumed above.
  const std::string waitingCodes = flow.substr(flow.size() - codes);
  CHECK(std::count_if(waitingCodes.begin(), waitingCodes.end(), [](char c) { return uint8_t(c) > 2; }) > 0);
  // Neither a triangle's sum nor a block of 1 to 8 cells a side (a tile's at most).
  for (const uint8_t code : {uint8_t(0), uint8_t(2), uint8_t(0x30), uint8_t(0x0f), uint8_t(0x19), uint8_t(0xff)}) {
    std::stringstream in(bytes + flow.substr(0, flow.size() - codes) + std::string(1, char(code)) + flow.substr(flow.size() - codes + 1));
    const uint64_t before = resumed.stateHash();
    CHECK_THROWS_WITH(resumed.loadState(in), "state is corrupt (waiting terrain volumes)");
    CHECK(resumed.stateHash() == before);
  }
  // A state of another step refused at its very end leaves the world's clock and particles alone.
  for (int k = 0; k < 3; ++k) resumed.step();
  const double before = resumed.time();
  CHECK(refuse(outside) == "state is corrupt (waiting terrain volumes)");
  CHECK(resumed.time() == before);
  CHECK(refuse(bytes) == "accepted");
  omp_set_num_threads(omp_get_num_procs());
}

TEST_CASE("DFSPH: the same at 1 and 2 threads, a resumed state steps on bit for bit, and the soil "
          "budget closes", "[determinism][dfsph]") {
  // The valley erodes, carries and deposits, with a source and a sink: every pass at work beside
  // the two solves, whose mean errors are summed in a fixed order.
  auto make = [] {
    Scene s = makePreset("valley", 0.3);
    s.desc.params.solver = FluidSolver::kDfsph;
    return std::make_unique<World>(s.desc);
  };
  auto run = [&](int threads, int steps) {
    omp_set_num_threads(threads);
    auto w = make();
    for (int k = 0; k < steps; ++k) w->step();
    return w;
  };
  const auto two = run(2, 200);
  CHECK(two->densitySolve().iterations > 0);
  CHECK(two->lastDt() > 2 * two->params().cfl * two->params().support() / two->params().sound_speed);
  const SoilBudget s = two->soilBudget();
  INFO("suspended " << s.suspended << ", error " << s.relativeError());
  CHECK(s.suspended > 0);
  CHECK(s.relativeError() < 1e-12);
  CHECK(run(1, 200)->stateHash() == two->stateHash());
  // The pressure means another thing to each solver: switching is a reset, not a live edit.
  SimParams other = two->params();
  other.solver = FluidSolver::kWcsph;
  CHECK_THROWS_WITH(two->setParams(other), "fluid.solver changes with a reset");
  // The warm start (last step's pressure) travels with the state: a resumed run is the same run.
  std::stringstream state;
  two->saveState(state);
  auto resumed = make();
  resumed->loadState(state);
  for (int k = 0; k < 40; ++k) two->step(), resumed->step();
  CHECK(resumed->stateHash() == two->stateHash());
  omp_set_num_threads(omp_get_num_procs());
}
