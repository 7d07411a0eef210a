// A tank of still water: after settling, the particle pressure follows p = ρ0 g (H − y) within 5 %
// in the lower 80 % of the column. H is the depth the water's volume fills (N Δs³ / tank area),
// and the profile is averaged over the last 0.5 s in layers one Δs thick.
#include <catch2/catch.hpp>
#include <cmath>

#include "scene/presets.h"

using namespace scour;

TEST_CASE("hydrostatic tank settles to the hydrostatic pressure profile", "[physics][hydrostatic]") {
  // Both solvers: WCSPH's pressure is the compressed water's, DFSPH's what its density solve needed.
  const FluidSolver solver = GENERATE(FluidSolver::kWcsph, FluidSolver::kDfsph);
  INFO((solver == FluidSolver::kDfsph ? "dfsph" : "wcsph"));
  Scene s = makePreset("hydrostatic");
  s.desc.params.solver = solver;
  const double ds = s.desc.params.spacing, g = s.desc.params.gravity;
  const double rho0 = s.desc.params.rest_density;
  const Heightfield& hf = s.desc.terrain;
  const double area = (hf.xMax() - hf.x0()) * (hf.zMax() - hf.z0());
  const double H = double(s.desc.particles.size()) * ds * ds * ds / area;
  World w(s.desc);
  const double settle = 1.5, average = 0.5;
  const int layers = int(std::ceil(H / ds)) + 2;
  std::vector<double> sumP(layers, 0), sumY(layers, 0);
  std::vector<long> count(layers, 0);
  while (w.time() < settle + average) {
    w.step();
    if (w.time() < settle || w.steps() % 10) continue;
    const Fluid& f = w.fluid();
    for (size_t i = 0; i < f.size(); ++i) {
      int b = int(f.x[i].y() / ds);
      if (b < 0 || b >= layers) continue;
      sumP[b] += f.p[i];
      sumY[b] += f.x[i].y();
      ++count[b];
    }
  }
  int checked = 0;
  for (int b = 0; b < layers; ++b) {
    if (count[b] == 0) continue;
    double y = sumY[b] / count[b], p = sumP[b] / count[b];
    if (y > 0.8 * H) continue;
    double expect = rho0 * g * (H - y);
    INFO("layer at y = " << y << ": p = " << p << " Pa, ρ0 g (H − y) = " << expect << " Pa");
    CHECK(std::abs(p / expect - 1.0) < 0.05);
    ++checked;
  }
  CHECK(checked >= 15);  // 0.8 H / Δs layers
  // Settled: nothing moves faster than a few cm/s.
  float vmax = 0;
  for (const auto& v : w.fluid().v) vmax = std::max(vmax, v.norm());
  CHECK(vmax < 0.1f);
  if (solver == FluidSolver::kDfsph) {
    // The solves held their tolerances, and the steps were the velocity's, not the sound's.
    CHECK(w.densitySolve().error <= s.desc.params.max_density_error);
    CHECK(w.lastDt() > 2 * s.desc.params.cfl * s.desc.params.support() / s.desc.params.sound_speed);
  }
}

TEST_CASE("without gravity a tank of still water stays still", "[physics][hydrostatic]") {
  // g = 0 is a slider's end: the wall's hydrostatic term divided the free surface's p = 0 by
  // ρ0 g h and made the accelerations NaN (a crash in the terrain lookup followed).
  Scene s = makePreset("hydrostatic");
  s.desc.params.gravity = 0;
  s.desc.pressure.clear();  // at rest without weight: no pressure
  World w(s.desc);
  for (int k = 0; k < 50; ++k) w.step();
  float vmax = 0;
  for (size_t i = 0; i < w.fluid().size(); ++i) {
    REQUIRE(w.fluid().x[i].allFinite());
    REQUIRE(w.fluid().v[i].allFinite());
    vmax = std::max(vmax, w.fluid().v[i].norm());
  }
  INFO("fastest particle " << vmax << " m/s");
  CHECK(vmax < 1e-3f);
  CHECK(w.invariants().nan == 0);
}
