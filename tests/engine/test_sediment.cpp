// Sediment transport on a frozen lattice (the paper's Figures 4 and 5): settling moves sediment
// down and only down at |v_s| of eq. (17); diffusion spreads a pulse with variance growing 2·D·t
// per axis; both conserve the sediment volume to rounding.
#include <catch2/catch.hpp>
#include <cmath>

#include "scene/presets.h"

using namespace scour;

namespace {
double totalSediment(const World& w) {
  double s = 0;
  for (double v : w.fluid().sed) s += v;
  return s;
}
}  // namespace

TEST_CASE("settling moves sediment down at the settling speed", "[sediment][settling]") {
  Scene s = makePreset("settling");
  World w(s.desc);
  const SimParams& p = w.params();
  const double vs = p.settlingSpeed(), h = p.support();
  const double s0 = totalSediment(w);
  const Fluid& f = w.fluid();
  size_t source = 0;
  for (size_t i = 0; i < f.size(); ++i)
    if (f.sed[i] > 0) source = i;
  const float ySource = f.x[source].y();
  auto centroid = [&] {
    double sy = 0, s = 0;
    for (size_t i = 0; i < f.size(); ++i) sy += f.sed[i] * f.x[i].y(), s += f.sed[i];
    return sy / s;
  };
  // Away from the bottom: between one h below the start and 3h above the floor.
  std::vector<std::pair<double, double>> samples;  // (t, centroid)
  while (centroid() > 3 * h) {
    w.step();
    for (size_t i = 0; i < f.size(); ++i)
      if (i != source && f.x[i].y() >= ySource - 1e-6f) REQUIRE(f.sed[i] == 0.0);  // only down
    REQUIRE(std::abs(totalSediment(w) - s0) <= 1e-12 * s0);
    if (centroid() < ySource - h) samples.emplace_back(w.time(), centroid());
    REQUIRE(w.time() < 100.0);
  }
  REQUIRE(samples.size() > 10);
  // Least-squares slope of the centroid against time.
  double st = 0, sy = 0, stt = 0, sty = 0, n = double(samples.size());
  for (auto [t, y] : samples) st += t, sy += y, stt += t * t, sty += t * y;
  double speed = -(n * sty - st * sy) / (n * stt - st * st);
  INFO("centroid speed " << speed << " m/s, |v_s| = " << vs << " m/s");
  CHECK(std::abs(speed / vs - 1.0) < 0.15);
  CHECK(w.invariants().c_min >= 0.0);
  CHECK(w.invariants().c_max <= p.c_max);
  // The fluid never moved: only the sediment passes ran.
  CHECK(w.passCalls()[size_t(Pass::kForces)] == 0);  // frozen: never
  CHECK(w.passCalls()[size_t(Pass::kSediment)] == w.steps());
  WARN("settling: centroid speed / |v_s| = " << speed / vs);
}

TEST_CASE("diffusion spreads a pulse with variance 2·D·t per axis", "[sediment][diffusion]") {
  Scene s = makePreset("diffusion");
  World w(s.desc);
  const double D = w.params().diffusion, h = w.params().support();
  const double s0 = totalSediment(w);
  const Fluid& f = w.fluid();
  Eigen::Vector3d c0 = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < f.size(); ++i) c0 += f.sed[i] * f.x[i].cast<double>();
  c0 /= s0;
  auto variance = [&] {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < f.size(); ++i)
      v += f.sed[i] * (f.x[i].cast<double>() - c0).cwiseAbs2();
    return Eigen::Vector3d(v / totalSediment(w));
  };
  // Once the pulse covers a few h (σ ≈ 1.5 h), measure the growth over the next stretch.
  while (variance().mean() < std::pow(1.5 * h, 2)) w.step();
  const double t1 = w.time();
  const Eigen::Vector3d v1 = variance();
  while (w.time() < t1 + 0.4) w.step();
  const Eigen::Vector3d growth = (variance() - v1) / (w.time() - t1);
  for (int a = 0; a < 3; ++a) {
    INFO("axis " << a << ": dσ²/dt = " << growth[a] << ", 2D = " << 2 * D);
    CHECK(std::abs(growth[a] / (2 * D) - 1.0) < 0.10);
  }
  // Symmetric: the centroid stays put and the three axes agree.
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < f.size(); ++i) c += f.sed[i] * f.x[i].cast<double>();
  c /= totalSediment(w);
  CHECK((c - c0).norm() < 1e-5);  // float lattice positions: ~1e-6 Δs
  CHECK(std::abs(growth[0] - growth[2]) < 1e-6 * growth[0]);
  CHECK(std::abs(totalSediment(w) - s0) <= 1e-12 * s0);
  WARN("diffusion: dσ²/dt / 2D = " << growth.transpose() / (2 * D));
}
