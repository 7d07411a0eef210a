#include "engine/sph.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scour {


SphConstants::SphConstants(const SimParams& p)
    : h(p.support()),
      mass(0),
      rho0(p.rest_density),
      c2(p.sound_speed * p.sound_speed),
      tait_b(p.rest_density * p.sound_speed * p.sound_speed / 7.0),
      delta(p.density_diffusion),
      continuity(p.density == DensityMethod::kContinuity),
      tait(p.eos == EquationOfState::kTait),
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
  mass = p.particleMass();
  // The spiky gradient, like any kernel gradient, should satisfy Σ_j V_j (x_j − x_i) ⊗ ∇W_ij = I
  // on the rest lattice, so that a linear pressure field gives back its gradient. At h = 2Δs it
  // misses by ~15 %, and a still column then settles at 15 % more than hydrostatic pressure.
  // Rescale it (per axis the lattice is isotropic, so one factor serves).
  {
    const int K = int(std::ceil(h / p.spacing));
    const double vol = mass / rho0;
    double s = 0;
    for (int c = -K; c <= K; ++c)
      for (int b = -K; b <= K; ++b)
        for (int a = -K; a <= K; ++a) {
          double r = p.spacing * std::sqrt(double(a * a + b * b + c * c));
          if (r > 0) s += -vol * (a * p.spacing) * (a * p.spacing) / r * spiky(float(r));
        }
    spiky.coef = float(spiky.coef / s);
  }
  buildWallTables(p.spacing);
}

void SphConstants::buildWallTables(double ds) {
  // Φ(d), for the summation density: the rest lattice's layers at offset k·Δs along the normal,
  // each standing for a slab [z − Δs/2, z + Δs/2] (z = d + kΔs its distance from the wall) whose
  // share beyond the wall is missing. A particle resting on the lattice next to a wall then reads
  // ρ0 exactly.
  const int K = int(std::ceil(h / ds)) + 1;
  std::vector<double> L(2 * K + 1, 0.0);
  double total = 0;
  for (int k = -K; k <= K; ++k)
    for (int b = -K; b <= K; ++b)
      for (int a = -K; a <= K; ++a) {
        double r = ds * std::sqrt(double(a * a + b * b + k * k));
        double w = poly6(float(r * r));
        L[k + K] += w;
        total += w;
      }
  // G(d), M_n(d), M_t(d), for the forces: continuum integrals over the half-space beyond the
  // wall, sliced along the normal (slice z < −d is beyond). Smooth in d, which keeps the wall
  // quiet; a lattice version has kinks at the slab edges that make it ring.
  const int nz = 1000, nr = 200;
  const double dz = 2.0 * h / nz;
  std::vector<double> sliceG(nz), sliceN(nz), sliceT(nz), sliceZ(nz);
  for (int a = 0; a < nz; ++a) {
    const double z = -h + (a + 0.5) * dz;
    const double R = std::sqrt(std::max(h * h - z * z, 0.0)), dr = R / nr;
    double g = 0, mn = 0, mt = 0;
    for (int b = 0; b < nr; ++b) {
      const double rho = (b + 0.5) * dr, r = std::sqrt(rho * rho + z * z);
      const double dw = -spiky(float(r)), ring = 2.0 * std::numbers::pi * rho * dr;
      g += dw * std::abs(z) / r * ring;
      mn += dw * z * z / r * ring;
      mt += dw * 0.5 * rho * rho / r * ring;  // x² averaged over the ring
    }
    sliceZ[a] = z;
    sliceG[a] = g * dz;
    sliceN[a] = mn * dz;
    sliceT[a] = mt * dz;
  }
  phi.assign(kTable + 1, 0.0);
  grad.assign(kTable + 1, 0.0);
  momentN.assign(kTable + 1, 0.0);
  momentT.assign(kTable + 1, 0.0);
  for (int t = 0; t <= kTable; ++t) {
    const double d = -h + 2.0 * h * t / kTable;
    double missing = 0;
    for (int k = -K; k <= K; ++k) missing += std::clamp(0.5 - (d + k * ds) / ds, 0.0, 1.0) * L[k + K];
    phi[t] = missing / total;
    // Slices below the particle (z < 0) would push it away from the wall, slices above it
    // (beyond the wall only once it has penetrated) toward it.
    double g = 0, mn = 0, mt = 0;
    for (int a = 0; a < nz && sliceZ[a] < -d; ++a) {
      g += (sliceZ[a] < 0 ? 1.0 : -1.0) * sliceG[a];
      mn += sliceN[a];
      mt += sliceT[a];
    }
    grad[t] = std::max(g, 0.0) * rho0 / mass;  // per unit particle mass, like a lattice sum
    momentN[t] = mn;
    momentT[t] = mt;
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
    f.rho[i] = float(rho);
    f.p[i] = float(k.pressure(rho));
  }
}

double integrateDensity(const SphConstants& k, const NeighborLists& nbrs, const Heightfield& hf,
                        const Domain& dom, const std::vector<Vec3f>& v, double dt, Fluid& f) {
  const size_t n = f.size();
  const float m = float(k.mass);
  const float diffusion = float(k.delta * k.h * std::sqrt(k.c2));
  const float hydro = float(k.rho0 * k.gravity / k.c2);
  // η² = 0.01 h² (Molteni & Colagrossi 2009) keeps ψ_ij = 2(ρ_j − ρ_i) x_ji/(r² + η²) finite as
  // two particles meet: without it the term grows as 1/r, and a splash particle (ρ0/2) driven
  // into a compressed one took the latter from 1012 to 2874 kg/m³ in one step (docs/model.md).
  const float eta2 = float(0.01 * k.h * k.h);
  std::vector<float>& next = f.scratch;
  resizeForParticles(next, n);
  double maxRate = 0.0;
#pragma omp parallel for schedule(static) reduction(max : maxRate)
  for (size_t i = 0; i < n; ++i) {
    const Vec3f vi = v[i];
    const float rhoi = f.rho[i];
    float div = 0.0f, diff = 0.0f;
    forEachNeighbor(nbrs, f.x, f.x, i, [&](uint32_t j, const Vec3f& xij, float r) {
      if (r <= 0.0f) return;
      const float dw = k.spiky(r);  // dW/dr ≤ 0; ∇_i W_ij = x_ij/r · dW/dr
      div += m * (vi - v[j]).dot(xij) * (dw / r);
      // δ-SPH (Molteni & Colagrossi 2009): ψ_ij·∇_i W_ij V_j, ψ_ij = 2(ρ_j − ρ_i) x_ji/(r² + η²),
      // less the hydrostatic density difference ρ0 g (y_i − y_j)/c_s² (Fourtakas et al. 2019):
      // near a wall or the surface the truncated sum would otherwise diffuse the hydrostatic
      // stratification away and the bottom layers would lose pressure.
      const float drho = f.rho[j] - rhoi - hydro * xij.y();
      diff += -2.0f * drho * (dw * r / (r * r + eta2)) * (m / f.rho[j]);
    });
    // A wall at rest adds ρ0 v_i·∫∇_i W over the half-space beyond it = −ρ0 A(d) (v_i·n).
    double wall = 0.0;
    forEachWall(hf, dom, k.h, f.x[i], [&](const Eigen::Vector3d& nrm, double d) {
      wall -= k.rho0 * k.planeDensity(d) * vi.cast<double>().dot(nrm);
    });
    const double rate = double(div) + double(diffusion * diff) + wall;
    double rho = rhoi + dt * rate;
    // A particle held at the floor below is not changing density: it does not bound Δt.
    if (rho >= 0.5 * k.rho0) maxRate = std::max(maxRate, std::abs(rate) / rhoi);
    // Floor at ρ0/2: below ρ0 the pressure is 0 anyway, but a splash particle leaving a wall
    // keeps losing continuity density through the wall term and would reach 0 or below, where
    // ρ0/ρ (wall support) and m/ρ (viscosity) blow up (docs/model.md; `scour stress`).
    next[i] = float(std::max(rho, 0.5 * k.rho0));
  }
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    f.rho[i] = next[i];
    f.p[i] = float(k.pressure(next[i]));
  }
  return maxRate;
}

double SphConstants::pressure(double rho) const {
  double pr = tait ? tait_b * (std::pow(rho / rho0, 7.0) - 1.0) : c2 * (rho - rho0);
  return std::max(pr, 0.0);  // free surface: no tension from the equation of state
}

double SphConstants::densityFor(double pressure) const {
  return tait ? rho0 * std::pow(1.0 + pressure / tait_b, 1.0 / 7.0) : rho0 + pressure / c2;
}

double SphConstants::planeDensity(double d) const {
  // A(d) = ∫ W_poly6 over a plane at distance |d| = (π c / 4)(h² − d²)⁴, c the poly6 constant:
  // the continuum −dΦ/dd. (The lattice table's own derivative has kinks at the slab edges, which
  // make the wall ring.)
  if (std::abs(d) >= h) return 0.0;
  double e = h * h - d * d;
  return std::numbers::pi / 4.0 * 315.0 / (64.0 * std::numbers::pi * std::pow(h, 9)) * e * e * e * e;
}

void computeForces(const SphConstants& k, const NeighborLists& nbrs,
                   const std::vector<Vec3f>& vhat, Fluid& f, bool pressure) {
  const size_t n = f.size();
  const float m = float(k.mass);
  const bool tension = k.kappa > 0.0f;
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    const float pi_rho2 = pressure ? f.p[i] / (f.rho[i] * f.rho[i]) : 0.0f;
    const Vec3f vi = vhat[i];
    Vec3f ap = Vec3f::Zero(), av = Vec3f::Zero(), at = Vec3f::Zero();
    forEachNeighbor(nbrs, f.x, f.x, i, [&](uint32_t j, const Vec3f& xij, float r) {
      if (r <= 0.0f) return;
      // Symmetric pressure term: −Σ m (p_i/ρ_i² + p_j/ρ_j²) ∇W_spiky.
      const float pj_rho2 = pressure ? f.p[j] / (f.rho[j] * f.rho[j]) : 0.0f;
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
                         const std::vector<Vec3f>& vhat, Fluid& f, bool pressure) {
  const size_t n = f.size();
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    const double mirrored = 2.0 * k.mass * f.p[i] / (double(f.rho[i]) * f.rho[i]);
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    const Eigen::Vector3d v = vhat[i].cast<double>();
    // The mirrored hydrostatic pressure below holds only where the pressure exceeds its rise
    // across the kernel; a particle at the free surface (a splash) gets a proportional share.
    // (Without gravity there is no growth to add, and a free surface's p = 0 over 0 was NaN.)
    const double support = k.gravity > 0 ? std::clamp(double(f.p[i]) / (k.rho0 * k.gravity * k.h), 0.0, 1.0) : 0.0;
    const double rhoRatio = support * k.rho0 / f.rho[i];
    forEachWall(hf, dom, k.h, f.x[i], [&](const Eigen::Vector3d& nrm, double d) {
      if (pressure) acc += mirrored * k.wallGradient(d) * nrm;
      // The mirrored pressure grows hydrostatically into the wall, p_j = p_i + ρ0 g⃗·(x_j − x_i);
      // its share of the gradient is −(ρ0/ρ_i) M(d) g⃗, M the missing second moment of the
      // kernel-gradient identity. Without it, water along a vertical wall loses part of its
      // support against gravity and sinks in a steady convection cell (with either solver: DFSPH
      // mirrors κ_i, not its growth).
      const double mn = k.momentNormal(d), mt = k.momentTangential(d);
      const Eigen::Vector3d g(0.0, -k.gravity, 0.0);
      acc -= rhoRatio * (mt * g + (mn - mt) * nrm.dot(g) * nrm);
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
