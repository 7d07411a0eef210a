// The equation-of-state choices and Becker–Teschner surface tension.
#include <catch2/catch.hpp>
#include <cmath>

#include "scene/presets.h"

using namespace scour;

TEST_CASE("both equations of state give their pressure and invert", "[fluid]") {
  SimParams p;
  p.sound_speed = 25.0;
  SphConstants tait(p);
  const double B = 1000.0 * 25.0 * 25.0 / 7.0;
  CHECK(tait.pressure(1010.0) == Approx(B * (std::pow(1.01, 7.0) - 1.0)).epsilon(1e-12));
  CHECK(tait.pressure(990.0) == 0.0);  // no tension at a free surface
  CHECK(tait.pressure(tait.densityFor(1234.5)) == Approx(1234.5).epsilon(1e-9));
  p.eos = EquationOfState::kIdealGas;  // Müller's ideal gas
  SphConstants gas(p);
  CHECK(gas.pressure(1010.0) == Approx(625.0 * 10.0).epsilon(1e-12));
  CHECK(gas.pressure(gas.densityFor(1234.5)) == Approx(1234.5).epsilon(1e-9));
}

TEST_CASE("the ideal-gas equation of state also holds a tank of water still", "[fluid]") {
  Scene s = makePreset("hydrostatic", 0.3);
  s.desc.params.eos = EquationOfState::kIdealGas;
  World w(s.desc);
  while (w.time() < 0.5) REQUIRE_NOTHROW(w.step());
  float vmax = 0;
  for (const auto& v : w.fluid().v) vmax = std::max(vmax, v.norm());
  CHECK(vmax < 0.3f);
}

TEST_CASE("surface tension pulls surface particles inward, in proportion to κ", "[fluid]") {
  // A weightless cube at rest: every particle reads ρ0 and p = 0, so the only force is cohesion.
  auto accel = [](double kappa) {
    SceneSpec spec;
    spec.params.spacing = 0.01;
    spec.params.gravity = 0.0;
    spec.params.surface_tension = kappa;
    spec.effects.surface_tension = kappa > 0;
    spec.terrain = flatTerrain(0.4, 0.4, 0.05);
    spec.blocks.push_back({{0.15, 0.15, 0.15}, {0.25, 0.25, 0.25}});
    World w(buildScene(spec).desc);
    return w.fluid();
  };
  const Fluid none = accel(0.0), one = accel(0.01), two = accel(0.02);
  const Eigen::Vector3f centre(0.2f, 0.2f, 0.2f);
  size_t cornerI = 0, middleI = 0;
  for (size_t i = 0; i < one.size(); ++i) {
    if ((one.x[i] - centre).norm() > (one.x[cornerI] - centre).norm()) cornerI = i;
    if ((one.x[i] - centre).norm() < (one.x[middleI] - centre).norm()) middleI = i;
  }
  CHECK(none.a[cornerI].norm() == 0.0f);
  const Eigen::Vector3f inward = (centre - one.x[cornerI]).normalized();
  CHECK(one.a[cornerI].normalized().dot(inward) > 0.99f);  // along the diagonal, inward
  CHECK(two.a[cornerI].norm() == Approx(2.0 * one.a[cornerI].norm()).epsilon(1e-5));
  CHECK(one.a[middleI].norm() < 1e-3f * one.a[cornerI].norm());  // balanced inside
}
