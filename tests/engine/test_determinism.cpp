// The same scene gives a bit-identical state at 1 and 2 OpenMP threads: sources, sinks, no-slip
// friction, Z-order reordering, the boundary tiles, erosion, settling, diffusion and deposition
// all run in the default scene.
#include <catch2/catch.hpp>
#include <omp.h>

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
  for (const char* preset : {"default", "dambreak"}) {
    INFO(preset);
    uint64_t one = hashAfter(preset, 1, 400);
    uint64_t two = hashAfter(preset, 2, 400);
    CHECK(one == two);
    CHECK(one != hashAfter(preset, 2, 399));  // the hash does see the state
  }
  omp_set_num_threads(omp_get_num_procs());
}
