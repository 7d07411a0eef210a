#pragma once
// SPH smoothing kernels, all with compact support radius h (W = 0 for r ≥ h).
//  - poly6, spiky gradient and viscosity Laplacian: Müller, Charypar, Gross 2003, used for
//    density, pressure force and viscosity respectively (paper §3).
//  - cubic spline (Monaghan 2005) and its radial derivative F = dW/dr, used by the sediment terms
//    (eqs. 16, 19). Monaghan writes the spline with support 2·h_M; here h_M = h/2 so that every
//    kernel in the engine shares one support radius and one neighbor list.
// Each kernel struct precomputes its normalisation for one h, so the inner loops are a few FLOPs.

#include <cmath>
#include <numbers>

namespace scour {

struct Poly6 {
  float h2 = 0, coef = 0;
  explicit Poly6(double h)
      : h2(float(h * h)), coef(float(315.0 / (64.0 * std::numbers::pi * std::pow(h, 9)))) {}
  /// W(r) from r².
  float operator()(float r2) const {
    if (r2 >= h2) return 0.0f;
    float d = h2 - r2;
    return coef * d * d * d;
  }
};

struct SpikyGrad {
  float h = 0, coef = 0;
  explicit SpikyGrad(double hh) : h(float(hh)), coef(float(-45.0 / (std::numbers::pi * std::pow(hh, 6)))) {}
  /// dW/dr (≤ 0); ∇W = r̂ · dW/dr.
  float operator()(float r) const {
    if (r >= h) return 0.0f;
    float d = h - r;
    return coef * d * d;
  }
};

struct ViscosityLaplacian {
  float h = 0, coef = 0;
  explicit ViscosityLaplacian(double hh)
      : h(float(hh)), coef(float(45.0 / (std::numbers::pi * std::pow(hh, 6)))) {}
  float operator()(float r) const { return r >= h ? 0.0f : coef * (h - r); }
};

/// Monaghan's cubic spline with support h (h_M = h/2), in double: the sediment fluxes
/// accumulate in double so that conservation holds to rounding.
struct CubicSpline {
  double hm = 0, sigma = 0;
  explicit CubicSpline(double h) : hm(0.5 * h), sigma(1.0 / (std::numbers::pi * hm * hm * hm)) {}
  double W(double r) const {
    double q = r / hm;
    if (q >= 2.0) return 0.0;
    if (q < 1.0) return sigma * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
    double t = 2.0 - q;
    return sigma * 0.25 * t * t * t;
  }
  /// F = dW/dr ≤ 0, so that ∇W(r_ij) = r̂_ij F(|r_ij|).
  double F(double r) const {
    double q = r / hm;
    if (q >= 2.0) return 0.0;
    if (q < 1.0) return sigma / hm * (-3.0 * q + 2.25 * q * q);
    double t = 2.0 - q;
    return -sigma / hm * 0.75 * t * t;
  }
};

}  // namespace scour
