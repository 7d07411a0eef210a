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
    {"default", 0.3, 100, 0x548e18f2a4cc431fULL, 0x1.47e26fd9f5a82p-1, 0x1.266c1d8383c5p-21},
    {"dambreak", 0.3, 100, 0x2b078af159c536c7ULL, -0x1.19314b5efb256p-28, 0x1.19314b5efb24fp-28},
    {"hydrostatic", 0.3, 100, 0x9d2424a47d023239ULL, -0x1.c7ff5c6899d27p-28, 0x1.c7ff5c6899d2ap-28},
    {"slope", 0.3, 100, 0xc5428999de1a7a4ULL, 0x1.47e270bcd4457p-1, 0x1.183e33ad001a1p-21},
    {"block", 0.05, 100, 0xf35c1e40325bcb04ULL, 0x1.65846d4d77002p-6, 0x1.29e4d148da4e4p-18},
    {"settling", 1, 100, 0xe277bb6544e7d18ULL, 0x1.0e073ea9e9142p-69, 0x1.9f5ebf27e9c15p-15},
    {"diffusion", 1, 100, 0x42e8539bdf9de0edULL, 0x1.1099b223fca6bp-18, 0x1.017a0414aa208p-11},
    {"canyon", 0.03, 100, 0xc01b13f02bdd2479ULL, 0x1.8eb991aa74c82p+5, 0x1.003ae6e84cd53p-19},
    {"lake", 0.03, 100, 0x4b77b1cf73842350ULL, 0x1.dc3997ea73506p+2, 0x1.f9792e926f449p-24},
    {"waterfall", 0.01, 100, 0x3bea95429af3342aULL, 0x1.443cbf6b28279p+4, 0x1.107872639bcfbp-17},
    {"rain", 0.3, 100, 0x162d245d9f6accb7ULL, 0x1.68b361849d5dap-1, 0x1.539275bed8e86p-24},
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
