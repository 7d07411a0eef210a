// Kernel properties, for every kernel the engine uses: the lattice integral of W is 1, the
// lattice sum of ∇W vanishes, and the analytic derivatives match finite differences.
#include <catch2/catch.hpp>
#include <cmath>

#include <Eigen/Core>

#include "engine/kernels.h"

using namespace scour;

namespace {
// Σ over a cubic lattice of spacing d (offset so no point sits at the origin by accident).
template <class F>
double latticeIntegral(double h, double d, const Eigen::Vector3d& offset, F&& f) {
  int K = int(std::ceil(h / d)) + 1;
  double s = 0;
  for (int c = -K; c <= K; ++c)
    for (int b = -K; b <= K; ++b)
      for (int a = -K; a <= K; ++a) s += f(Eigen::Vector3d(a * d, b * d, c * d) + offset) * d * d * d;
  return s;
}
const Eigen::Vector3d kOffset(0.013, -0.021, 0.007);  // in units of h below
}  // namespace

TEST_CASE("every kernel integrates to 1", "[kernels]") {
  const double h = 0.1, d = h / 40;
  Poly6 poly6(h);
  CubicSpline spline(h);
  // Spiky and viscosity kernels' values are not used, only their derivatives; their values are
  // checked through the derivatives below.
  CHECK(latticeIntegral(h, d, kOffset * h, [&](const Eigen::Vector3d& r) {
          return double(poly6(float(r.squaredNorm())));
        }) == Approx(1.0).epsilon(2e-3));
  CHECK(latticeIntegral(h, d, kOffset * h, [&](const Eigen::Vector3d& r) {
          return spline.W(r.norm());
        }) == Approx(1.0).epsilon(2e-3));
}

TEST_CASE("the gradient sums to zero and F matches a finite difference", "[kernels]") {
  const double h = 0.1, d = h / 20;
  SpikyGrad spiky(h);
  CubicSpline spline(h);
  for (int axis = 0; axis < 3; ++axis) {
    double gs = latticeIntegral(h, d, Eigen::Vector3d::Zero(), [&](const Eigen::Vector3d& r) {
      double n = r.norm();
      return n > 0 ? spline.F(n) * r[axis] / n : 0.0;
    });
    double gp = latticeIntegral(h, d, Eigen::Vector3d::Zero(), [&](const Eigen::Vector3d& r) {
      double n = r.norm();
      return n > 0 ? double(spiky(float(n))) * r[axis] / n : 0.0;
    });
    CHECK(std::abs(gs) < 1e-9);
    CHECK(std::abs(gp) < 1e-6);
  }
  // Analytic derivatives against central differences of the kernel values.
  const double eps = 1e-6;
  Poly6 poly6(h);
  ViscosityLaplacian lap(h);
  for (double q : {0.05, 0.2, 0.45, 0.5, 0.55, 0.8, 0.97}) {
    double r = q * h;
    double fd = (spline.W(r + eps) - spline.W(r - eps)) / (2 * eps);
    CHECK(spline.F(r) == Approx(fd).epsilon(1e-5));
    CHECK(spline.F(r) <= 0.0);
    // Spiky: W = 15/(π h⁶)(h − r)³, so dW/dr = −45/(π h⁶)(h − r)².
    auto spikyW = [&](double rr) { return 15.0 / (M_PI * std::pow(h, 6)) * std::pow(h - rr, 3); };
    CHECK(double(spiky(float(r))) == Approx((spikyW(r + eps) - spikyW(r - eps)) / (2 * eps)).epsilon(1e-4));
    // Viscosity kernel: ∇²W = W'' + 2W'/r of W = 15/(2π h³)(−r³/2h³ + r²/h² + h/2r − 1).
    auto viscW = [&](double rr) {
      return 15.0 / (2 * M_PI * h * h * h) *
             (-rr * rr * rr / (2 * h * h * h) + rr * rr / (h * h) + h / (2 * rr) - 1);
    };
    double w1 = (viscW(r + 1e-5) - viscW(r - 1e-5)) / 2e-5;
    double w2 = (viscW(r + 1e-5) - 2 * viscW(r) + viscW(r - 1e-5)) / 1e-10;
    CHECK(double(lap(float(r))) == Approx(w2 + 2 * w1 / r).epsilon(2e-3));
  }
  // Poly6's own gradient against its values, through r² (the argument the engine uses).
  for (double q : {0.1, 0.5, 0.9}) {
    double r = q * h;
    double fd = (poly6(float((r + 1e-4) * (r + 1e-4))) - poly6(float((r - 1e-4) * (r - 1e-4)))) / 2e-4;
    double exact = -6.0 * 315.0 / (64 * M_PI * std::pow(h, 9)) * r * std::pow(h * h - r * r, 2);
    CHECK(fd == Approx(exact).epsilon(1e-2));
  }
  CHECK(poly6(float(h * h)) == 0.0f);
  CHECK(spline.W(h) == 0.0);
  CHECK(spline.F(h) == 0.0);
}
