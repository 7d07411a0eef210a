// The golden test: every preset, with every erosion effect on, run for a fixed number of steps,
// gives the state hash and soil budget recorded below, to the last bit. It guards behaviour while
// code moves (the app, the scenes and the World rebuilt). When physics changes on purpose, the
// failure prints the new line of each preset; paste them in that change's own commit and say
// why. SCOUR_GOLDEN_PRINT=1 prints every line.
#include <catch2/catch.hpp>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <set>
#include <sstream>

#include "scene/presets.h"

using namespace scour;

namespace {

struct Golden {
  const char* preset;
  double scale;
  int steps;
  uint64_t hash;
  double terrain, suspended;  // SoilBudget, m³
};

// Recorded at the commit that added this test (after the δ-SPH regularisation, the compressed
// sound speed in the CFL step and the wall envelope).
const Golden kGolden[] = {
    {"default", 0.3, 100, 0xea55bf3e1cfc477ULL, 0x1.47e26ff4aabfdp-1, 0x1.24c0cc0a105bap-21},
    {"dambreak", 0.3, 100, 0xfe9c92d6bd803e0dULL, -0x1.196fbeb4943cp-28, 0x1.196fbeb4943b6p-28},
    {"hydrostatic", 0.3, 100, 0xf2eec1f4d9523b2bULL, -0x1.d5441b49f7c83p-28, 0x1.d5441b49f7c7fp-28},
    {"slope", 0.3, 100, 0x3958653f927fc984ULL, 0x1.47e270cbf5207p-1, 0x1.174c25fd9e1dfp-21},
    {"block", 0.05, 100, 0x9428ce3c9067117ULL, 0x1.65833d5a26f0dp-6, 0x1.3ce40649d177p-18},
    {"settling", 1, 100, 0x8a9bab438f291d0dULL, 0x1.0971822b2a4d3p-68, 0x1.9f5ebf27e9c14p-15},
    {"diffusion", 1, 100, 0x2f0f91684bc06df5ULL, 0x1.e5679cacdfda3p-18, 0x1.ffa0d07f30b39p-12},
    {"canyon", 0.03, 100, 0x6fed055c1bcbea8dULL, 0x1.8eb9928a26389p+5, 0x1.49ed16979559cp-22},
    {"lake", 0.03, 100, 0x1c979de5586d9ebbULL, 0x1.dc39983557c59p+2, 0x1.9bceb8773479ap-25},
    {"waterfall", 0.01, 100, 0x9b9bd13e986d3f58ULL, 0x1.443cc733ae64ap+4, 0x1.767aaf70552f1p-21},
    {"rain", 0.3, 100, 0xa904496d14b0d005ULL, 0x1.68b361c96745fp-1, 0x1.312d81898973fp-24},
};

std::string line(const char* preset, double scale, int steps, uint64_t hash, const SoilBudget& b) {
  std::ostringstream o;
  o << "    {\"" << preset << "\", " << scale << ", " << steps << ", 0x" << std::hex << hash
    << "ULL, " << std::hexfloat << b.terrain << ", " << b.suspended << "},";
  return o.str();
}

}  // namespace

TEST_CASE("every preset reaches its recorded state hash and soil budget", "[golden]") {
  const bool print = std::getenv("SCOUR_GOLDEN_PRINT") != nullptr;
  std::set<std::string> covered;
  for (const Golden& g : kGolden) {
    INFO(g.preset);
    SceneSpec spec = presetSpec(g.preset, g.scale);
    Effects& fx = spec.effects;
    fx.erosion = fx.settling = fx.diffusion = fx.deposition = true;
    Scene s = buildScene(spec);
    World w(s.desc);
    for (int k = 0; k < g.steps; ++k) w.step();
    const SoilBudget b = w.soilBudget();
    const std::string now = line(g.preset, g.scale, g.steps, w.stateHash(), b);
    if (print) std::cout << now << "\n";
    INFO("now:\n" << now);
    CHECK(w.stateHash() == g.hash);
    CHECK(b.terrain == g.terrain);
    CHECK(b.suspended == g.suspended);
    CHECK(b.relativeError() < 1e-12);
    covered.insert(g.preset);
  }
  for (const PresetInfo& p : presetList()) {
    INFO("preset without a golden line: " << p.name);
    CHECK(covered.count(p.name) == 1);
  }
}
