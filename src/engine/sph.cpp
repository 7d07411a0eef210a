#include "engine/sph.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scour {

namespace {
// Σ W_poly6 over the cubic rest lattice of spacing Δs (self included) within support h.
double latticeSum(const Poly6& w, double spacing, double h) {
  int K = int(std::ceil(h / spacing));
  double s = 0;
  for (int c = -K; c <= K; ++c)
    for (int b = -K; b <= K; ++b)
      for (int a = -K; a <= K; ++a)
        s += w(float(spacing * spacing * (a * a + b * b + c * c)));
  return s;
}
}  // namespace

SphConstants::SphConstants(const SimParams& p)
    : h(p.support()),
      mass(0),
      rho0(p.rest_density),
      c2(p.sound_speed * p.sound_speed),
      tait_b(p.rest_density * p.sound_speed * p.sound_speed / 7.0),
      tait(p.equationOfState() == EquationOfState::kTait),
      nu(float(p.viscosity)),
      kappa(float(p.surface_tension)),
      gravity(float(p.gravity)),
      ks(float(p.penalty_stiffness)),
      kd(float(p.penalty_damping)),
      contact(float(p.contact_over_spacing * p.spacing)),
      friction(float(p.boundary_friction)),
      poly6(h),
      spiky(h),
      visc(h) {
  mass = p.rest_density / latticeSum(poly6, p.spacing, h);
  buildWallTables(p.spacing);
}

void SphConstants::buildWallTables(double ds) {
  // Layer sums of the rest lattice at vertical offset k·Δs: L_k = Σ W, D_k = Σ |dW/dr|·|kΔs|/r.
  const int K = int(std::ceil(h / ds)) + 1;
  std::vector<double> L(2 * K + 1, 0.0), D(2 * K + 1, 0.0);
  double total = 0;
  for (int k = -K; k <= K; ++k)
    for (int b = -K; b <= K; ++b)
      for (int a = -K; a <= K; ++a) {
        double r = ds * std::sqrt(double(a * a + b * b + k * k));
        double w = poly6(float(r * r));
        L[k + K] += w;
        total += w;
        if (r > 0) D[k + K] += -spiky(float(r)) * std::abs(k * ds) / r;
      }
  phi.assign(kTable + 1, 0.0);
  grad.assign(kTable + 1, 0.0);
  for (int t = 0; t <= kTable; ++t) {
    double d = -h + 2.0 * h * t / kTable;
    double missing = 0, missingGrad = 0;
    for (int k = -K; k < 0; ++k) {  // layers below the particle (toward the wall)
      // The layer's slab [z − Δs/2, z + Δs/2], z = d + kΔs its distance from the wall: the share
      // beyond the wall is missing.
      double z = d + k * ds;
      double beyond = std::clamp(0.5 - z / ds, 0.0, 1.0);
      missing += beyond * L[k + K];
      missingGrad += beyond * D[k + K];
    }
    // Layers at and above the particle can be beyond the wall only when it has penetrated.
    for (int k = 0; k <= K; ++k) {
      double z = d + k * ds;
      double beyond = std::clamp(0.5 - z / ds, 0.0, 1.0);
      missing += beyond * L[k + K];
      missingGrad -= beyond * D[k + K];
    }
    phi[t] = missing / total;
    grad[t] = std::max(missingGrad, 0.0);
  }
}

double SphConstants::lookup(const std::vector<double>& t, double d) const {
  double u = (d + h) / (2.0 * h) * kTable;
  if (u <= 0) return t.front();
  if (u >= kTable) return t.back();
  int i = int(u);
  double f = u - i;
  return t[i] * (1 - f) + t[i + 1] * f;
}

void computeDensity(const SphConstants& k, const NeighborLists& nbrs, const Heightfield& hf,
                    const Domain& dom, Fluid& f) {
  const size_t n = f.size();
  const float m = float(k.mass), self = m * k.poly6(0.0f);
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    float sum = 0.0f;
    const uint32_t* js = nbrs.begin(i);
    const Vec3f xi = f.x[i];
    for (uint32_t c = 0; c < nbrs.count(i); ++c) sum += k.poly6((xi - f.x[js[c]]).squaredNorm());
    double inside = 1.0;  // share of the lattice sum on the fluid side of every nearby plane
    forEachWall(hf, dom, k.h, xi, [&](const Eigen::Vector3d&, double d) {
      inside *= 1.0 - k.halfSpaceDensity(d);
    });
    double rho = self + m * sum + k.rho0 * (1.0 - inside);
    double pr = k.tait ? k.tait_b * (std::pow(rho / k.rho0, 7.0) - 1.0) : k.c2 * (rho - k.rho0);
    f.rho[i] = float(rho);
    f.p[i] = float(std::max(pr, 0.0));  // free surface: no tension from the equation of state
  }
}

void computeForces(const SphConstants& k, const NeighborLists& nbrs,
                   const std::vector<Vec3f>& vhat, Fluid& f) {
  const size_t n = f.size();
  const float m = float(k.mass);
  const bool tension = k.kappa > 0.0f;
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    const float pi_rho2 = f.p[i] / (f.rho[i] * f.rho[i]);
    const Vec3f vi = vhat[i];
    Vec3f ap = Vec3f::Zero(), av = Vec3f::Zero(), at = Vec3f::Zero();
    forEachNeighbor(nbrs, f.x, f.x, i, [&](uint32_t j, const Vec3f& xij, float r) {
      if (r <= 0.0f) return;
      // Symmetric pressure term: −Σ m (p_i/ρ_i² + p_j/ρ_j²) ∇W_spiky.
      const float pj_rho2 = f.p[j] / (f.rho[j] * f.rho[j]);
      ap -= (m * (pi_rho2 + pj_rho2) * k.spiky(r) / r) * xij;
      // Müller's viscosity with the viscosity-kernel Laplacian, kinematic form.
      av += (m / f.rho[j] * k.visc(r)) * (vhat[j] - vi);
      // Becker–Teschner cohesion: −(κ/m_i) Σ m_j (x_i − x_j) W(r_ij).
      if (tension) at -= (m * k.poly6(r * r)) * xij;
    });
    Vec3f a = ap + k.nu * av + (k.kappa / m) * at;
    a.y() -= k.gravity;
    f.a[i] = a;
  }
}

void applyBoundaryForces(const SphConstants& k, const Heightfield& hf, const Domain& dom,
                         const std::vector<Vec3f>& vhat, Fluid& f) {
  const size_t n = f.size();
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    const double pressure = 2.0 * k.mass * f.p[i] / (double(f.rho[i]) * f.rho[i]);
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    const Eigen::Vector3d v = vhat[i].cast<double>();
    forEachWall(hf, dom, k.h, f.x[i], [&](const Eigen::Vector3d& nrm, double d) {
      acc += pressure * k.wallGradient(d) * nrm;
      if (d < k.contact) {
        // Eq. (6): f_np = (K_S d − (v·n) K_D) n, damping only for an approaching particle.
        double vn = std::min(v.dot(nrm), 0.0);
        acc += (k.ks * (k.contact - d) - vn * k.kd) * nrm;
      }
    });
    f.a[i] += acc.cast<float>();
  }
}

void applyNoSlip(const SphConstants& k, const NeighborLists& bnbrs, const BoundaryParticles& b,
                 const std::vector<Vec3f>& vhat, Fluid& f) {
  const size_t n = f.size();
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    // Eq. (8): f_ns = Σ_b L_b² τ_visc, τ_visc = −μ_b v ∇²W_visc(|r − r_b|).
    float sum = 0.0f;
    forEachNeighbor(bnbrs, f.x, b.x, i, [&](uint32_t j, const Vec3f&, float r) {
      sum += float(b.area[j]) * k.visc(r);
    });
    f.a[i] -= (k.friction * sum) * vhat[i];
  }
}

}  // namespace scour
