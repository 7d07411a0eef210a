// Martin & Moyce (1952) dam break, a = 2.25 in: the surge front Z = z/a against T = t·√(2g/a)
// stays within 15 % of their measurements for T ≤ 5. The front is the largest x of any particle,
// measured from the left wall (x = 0), and interpolated between snapshots to the data's times.
#include <catch2/catch.hpp>
#include <cmath>

#include "scene/presets.h"

using namespace scour;

TEST_CASE("dam break front follows Martin & Moyce", "[physics][dambreak]") {
  const double a = 0.05715;
  const std::vector<std::pair<double, double>> data = {
      {0.832, 1.217}, {1.219, 1.474}, {1.997, 2.292}, {2.547, 2.995},
      {3.345, 4.134}, {4.034, 4.944}, {4.418, 5.881}, {5.091, 6.980}};
  // Both solvers; DFSPH at its default density error (0.1 %).
  const FluidSolver solver = GENERATE(FluidSolver::kWcsph, FluidSolver::kDfsph);
  INFO((solver == FluidSolver::kDfsph ? "dfsph" : "wcsph"));
  Scene s = makePreset("dambreak");
  s.desc.params.solver = solver;
  World w(s.desc);
  const double g = s.desc.params.gravity, tScale = std::sqrt(2.0 * g / a);
  std::vector<std::pair<double, double>> front;  // (T, Z)
  auto record = [&] {
    float xmax = 0;
    for (const auto& x : w.fluid().x) xmax = std::max(xmax, x.x());
    front.emplace_back(w.time() * tScale, xmax / a);
  };
  record();
  while (w.time() * tScale < 5.2) {
    w.step();
    record();
  }
  double worst = 0;
  for (auto [T, Z] : data) {
    if (T > 5.0) continue;
    auto it = std::lower_bound(front.begin(), front.end(), std::make_pair(T, -1e9));
    REQUIRE(it != front.begin());
    REQUIRE(it != front.end());
    auto [T1, Z1] = *it;
    auto [T0, Z0] = *(it - 1);
    double Zsim = Z0 + (Z1 - Z0) * (T - T0) / (T1 - T0);
    double err = std::abs(Zsim - Z) / Z;
    INFO("T = " << T << ": Z_sim = " << Zsim << ", Z_data = " << Z);
    CHECK(err < 0.15);
    worst = std::max(worst, err);
  }
  WARN("dam break (" << (solver == FluidSolver::kDfsph ? "dfsph" : "wcsph")
                      << "): worst relative front error for T ≤ 5 = " << worst);
}
