#include "engine/dfsph.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/parallel.h"

namespace scour {

DfsphConstants::DfsphConstants(const SphConstants& k, double spacing) : h(k.h), mass(k.mass), rho0(k.rho0) {
  const CubicSpline spline(h);
  hm = float(spline.hm);
  // The scale that makes the rest lattice read ρ0: m Σ_lattice W = ρ0.
  const int K = int(std::ceil(h / spacing));
  double sum = 0;
  for (int c = -K; c <= K; ++c)
    for (int b = -K; b <= K; ++b)
      for (int a = -K; a <= K; ++a) sum += spline.W(spacing * std::sqrt(double(a * a + b * b + c * c)));
  const double scale = rho0 / (mass * sum);
  w0 = float(scale * spline.sigma), f0 = float(scale * spline.sigma / spline.hm);
  // The walls' share Φ(d) and its slope, from the rest lattice (dfsph.h): a particle resting on
  // the lattice at d = (m + ½) Δs from a wall misses the layers at offsets k Δs, k > m, beyond it;
  // Φ there is their share of the lattice sum, and dΦ/dd their Σ m ∇W along the normal over ρ0,
  // so that the particle reads ρ0 and ∇ρ_i = 0, as in the bulk. Between these knots Φ is the cubic
  // that matches both (Hermite), so the density and the gradient stay one function's; Φ = 0 with
  // slope 0 at d = h, and Φ(−d) = 1 − Φ(d).
  const int layers = K + 1;
  std::vector<double> share(size_t(layers) + 1, 0.0), slope(size_t(layers) + 1, 0.0);
  for (int k = 0; k <= layers; ++k)
    for (int b = -K; b <= K; ++b)
      for (int a = -K; a <= K; ++a) {
        const double r = spacing * std::sqrt(double(a * a + b * b + k * k));
        share[size_t(k)] += mass * scale * spline.W(r) / rho0;
        if (r > 0) slope[size_t(k)] += mass * scale * spline.F(r) / r * (k * spacing) / rho0;
      }
  std::vector<double> knotD, knotPhi, knotSlope;  // d ≥ 0
  for (int m = 0; (m + 0.5) * spacing < h; ++m) {
    double phi = 0, dphi = 0;
    for (int k = m + 1; k <= layers; ++k) phi += share[size_t(k)], dphi += slope[size_t(k)];
    knotD.push_back((m + 0.5) * spacing), knotPhi.push_back(phi), knotSlope.push_back(dphi);
  }
  knotD.push_back(h), knotPhi.push_back(0.0), knotSlope.push_back(0.0);
  // Mirror: the knots over [−h, h].
  std::vector<double> D, P, S;
  for (size_t q = knotD.size(); q-- > 0;) D.push_back(-knotD[q]), P.push_back(1.0 - knotPhi[q]), S.push_back(knotSlope[q]);
  for (size_t q = 0; q < knotD.size(); ++q) D.push_back(knotD[q]), P.push_back(knotPhi[q]), S.push_back(knotSlope[q]);
  phi_.assign(kTable + 1, 0.0), rate_.assign(kTable + 1, 0.0);
  for (int t = 0; t <= kTable; ++t) {
    const double d = -h + 2.0 * h * t / kTable;
    size_t q = 0;
    while (q + 2 < D.size() && d > D[q + 1]) ++q;
    const double len = D[q + 1] - D[q], u = std::clamp((d - D[q]) / len, 0.0, 1.0);
    const double h00 = 2 * u * u * u - 3 * u * u + 1, h10 = u * u * u - 2 * u * u + u;
    const double h01 = -2 * u * u * u + 3 * u * u, h11 = u * u * u - u * u;
    phi_[size_t(t)] = h00 * P[q] + h10 * len * S[q] + h01 * P[q + 1] + h11 * len * S[q + 1];
    const double d00 = 6 * u * u - 6 * u, d10 = 3 * u * u - 4 * u + 1, d01 = -6 * u * u + 6 * u, d11 = 3 * u * u - 2 * u;
    rate_[size_t(t)] = -((d00 * P[q] + d01 * P[q + 1]) / len + d10 * S[q] + d11 * S[q + 1]);
  }
}

float DfsphConstants::W(float r) const {
  const float q = r / hm;
  if (q >= 2.0f) return 0.0f;
  if (q < 1.0f) return w0 * (1.0f - 1.5f * q * q + 0.75f * q * q * q);
  const float t = 2.0f - q;
  return w0 * 0.25f * t * t * t;
}

float DfsphConstants::gradOverR(float r) const {
  const float q = r / hm;
  if (q >= 2.0f || r <= 0.0f) return 0.0f;
  if (q < 1.0f) return f0 / hm * (-3.0f + 2.25f * q);
  const float t = 2.0f - q;
  return -f0 * 0.75f * t * t / r;
}

double DfsphConstants::lookup(const std::vector<double>& t, double d) const {
  const double u = std::clamp((d + h) / (2.0 * h), 0.0, 1.0) * kTable;
  const size_t i = std::min(size_t(u), size_t(kTable - 1));
  const double w = u - double(i);
  return t[i] + w * (t[i + 1] - t[i]);
}

namespace {

// Each Jacobi step takes this share of the κ change α promises (α is the diagonal of the system,
// the neighbours' κ taken as the particle's own). At 1 the projected iteration overshot and blew
// up in the still tank; IISPH relaxes by 0.5 too (Ihmsen et al. 2014).
constexpr double kRelaxation = 0.5;
// The warm start's share of last step's κ (SPlisHSPlasH's 0.5): the whole of it pushed a still
// tank into a slosh (rms 0.04 m/s against 0.004) that the solve then chased.
constexpr float kWarmShare = 0.5f;
// The walls mirror the particle's κ (κ_wall = κ_i), as WCSPH's wall pressure does: with κ_wall = 0
// (SPlisHSPlasH's choice) the bottom layer of a still tank carries 1.7 × its hydrostatic pressure.
// The solves' linearised density counts the wall's share of Dρ_i/Dt with the same factor, so the
// force stays the constraint's gradient and the system symmetric: with the factor in the force
// alone the Jacobi iteration diverged where walls dominate (`scour stress`, deep-column: more
// iterations, more energy). At rest (v = 0) the factor changes nothing.
constexpr float kWallMirror = 2.0f;
constexpr int kMinDensityIterations = 2;
constexpr int kMinDivergenceIterations = 1;

// Σ e in blocks of a fixed size, then over the blocks in order: the same bits at any thread count.
double orderedSum(const std::vector<float>& e) {
  constexpr size_t kBlock = 2048;
  const size_t n = e.size(), blocks = (n + kBlock - 1) / kBlock;
  std::vector<double> part(blocks, 0.0);
#pragma omp parallel for schedule(static)
  for (size_t b = 0; b < blocks; ++b) {
    double s = 0;
    for (size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) s += double(e[i]);
    part[b] = s;
  }
  double s = 0;
  for (double q : part) s += q;
  return s;
}

// Dρ_i/Dt = Σ_j m (v_i − v_j)·∇W_ij + v_i·g_w (the walls at rest).
float densityRate(const NeighborLists& nbrs, const Fluid& f, const DfsphWorkspace& w, size_t i) {
  const uint32_t* js = nbrs.begin(i);
  const Vec3f* g = w.grad.data() + w.first[i];
  const Vec3f vi = f.v[i];
  float rate = 0.0f;
  for (uint32_t c = 0; c < nbrs.count(i); ++c) rate += (vi - f.v[js[c]]).dot(g[c]);
  return rate + kWallMirror * vi.dot(w.wall[i]);
}

// v_i −= Δt (Σ_j m (c_i/ρ_i + c_j/ρ_j) ∇W_ij + 2 c_i/ρ_i g_w): the velocity change of the κ change
// c. Reads only c and ρ, so each particle's update is its own.
void correct(const NeighborLists& nbrs, double dt, const std::vector<float>& c, Fluid& f, const DfsphWorkspace& w) {
  const size_t n = f.size();
  const float step = float(dt);
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    const float ci = c[i] / f.rho[i];
    Vec3f dv = (kWallMirror * ci) * w.wall[i];
    const uint32_t* js = nbrs.begin(i);
    const Vec3f* g = w.grad.data() + w.first[i];
    for (uint32_t q = 0; q < nbrs.count(i); ++q) {
      const uint32_t j = js[q];
      dv += (ci + c[j] / f.rho[j]) * g[q];
    }
    f.v[i] -= step * dv;
  }
}

// The Jacobi loop both solves share: `residual(i)` sets w.error[i] and w.change[i] for each
// particle; while the mean error is above `maxError` (or fewer than `minIterations` corrections
// ran), the change is applied to the velocities and `accept()` keeps it, up to `maxIterations`.
template <class Residual, class Accept>
SolveReport iterate(const DfsphConstants& k, const NeighborLists& nbrs, double dt, double maxError, int minIterations,
                    int maxIterations, Fluid& f, DfsphWorkspace& w, Residual&& residual, Accept&& accept) {
  const size_t n = f.size();
  SolveReport report;
  for (;;) {
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) residual(i);
    report.error = orderedSum(w.error) / double(n) / k.rho0;
    if ((report.error <= maxError && report.iterations >= minIterations) || report.iterations >= maxIterations)
      return report;
    correct(nbrs, dt, w.change, f, w);
    accept();
    ++report.iterations;
  }
}

}  // namespace

void dfsphFactors(const DfsphConstants& k, const NeighborLists& nbrs, const Heightfield& hf, const Domain& dom,
                  Fluid& f, DfsphWorkspace& w) {
  const size_t n = f.size();
  resizeForParticles(w.alpha, n), resizeForParticles(w.wall, n);
  const float m = float(k.mass);
  w.first.resize(n + 1);
  w.first[0] = 0;
  for (size_t i = 0; i < n; ++i) w.first[i + 1] = w.first[i] + nbrs.count(i);
  w.grad.resize(w.first[n]);
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    float rho = m * k.W(0.0f), g2 = 0.0f;
    Vec3f g = Vec3f::Zero();
    Vec3f* pair = w.grad.data() + w.first[i];
    forEachNeighbor(nbrs, f.x, f.x, i, [&](uint32_t, const Vec3f& xij, float r) {
      rho += m * k.W(r);  // a twin at r = 0 adds W(0) and no gradient
      const Vec3f grad = (m * k.gradOverR(r)) * xij;
      *pair++ = grad;
      g += grad;
      g2 += grad.squaredNorm();
    });
    // The walls' share ρ0 (1 − Π_k (1 − Φ_k)) and its gradient −ρ0 Σ_k A_k n_k Π_{l≠k} (1 − Φ_l).
    Eigen::Vector3d rateN[5];
    double keep[5];
    int walls = 0;
    forEachWall(hf, dom, k.h, f.x[i], [&](const Eigen::Vector3d& nrm, double d) {
      if (walls == 5) return;
      rateN[walls] = k.wallRate(d) * nrm;
      keep[walls++] = 1.0 - k.wallShare(d);
    });
    Eigen::Vector3d gw = Eigen::Vector3d::Zero();
    double all = 1.0;
    for (int a = 0; a < walls; ++a) {
      double others = 1.0;
      for (int b = 0; b < walls; ++b)
        if (b != a) others *= keep[b];
      gw -= others * rateN[a];
      all *= keep[a];
    }
    gw *= k.rho0;
    rho += float(k.rho0 * (1.0 - all));
    f.rho[i] = rho;
    w.wall[i] = gw.cast<float>();
    const Vec3f P = g + kWallMirror * w.wall[i];
    const double denom = double(P.squaredNorm()) + double(g2);
    w.alpha[i] = denom > 1e-9 * double(rho) * double(rho) / (k.h * k.h) ? float(double(rho) / denom) : 0.0f;
  }
}

SolveReport solveDensity(const DfsphConstants& k, const NeighborLists& nbrs, double dt, double maxError,
                         int maxIterations, Fluid& f, DfsphWorkspace& w) {
  const size_t n = f.size();
  if (n == 0) return {};
  resizeForParticles(w.change, n), resizeForParticles(w.error, n);
  std::vector<float>& kappa = f.p;  // κ = p/ρ during the solve
  const float rho0 = float(k.rho0), step = float(dt), perDt2 = float(kRelaxation / (dt * dt));
  // Warm start: last step's pressure where the water is compressed now.
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    const bool compressed = f.rho[i] + step * densityRate(nbrs, f, w, i) > rho0;
    w.change[i] = compressed ? kWarmShare * std::max(f.p[i], 0.0f) / f.rho[i] : 0.0f;
  }
  kappa = w.change;
  correct(nbrs, dt, w.change, f, w);
  // The density x + Δt v would have: its compression is the error; the κ change removes it.
  const SolveReport report = iterate(
      k, nbrs, dt, maxError, kMinDensityIterations, maxIterations, f, w,
      [&](size_t i) {
        const float predicted = f.rho[i] + step * densityRate(nbrs, f, w, i) - rho0;
        w.error[i] = std::max(predicted, 0.0f);
        w.change[i] = std::max(kappa[i] + predicted * w.alpha[i] * perDt2, 0.0f) - kappa[i];
      },
      [&] {
#pragma omp parallel for schedule(static) if (n >= kParallelFrom)
        for (size_t i = 0; i < n; ++i) kappa[i] += w.change[i];
      });
#pragma omp parallel for schedule(static) if (n >= kParallelFrom)
  for (size_t i = 0; i < n; ++i) f.p[i] = kappa[i] * f.rho[i];
  return report;
}

SolveReport solveDivergence(const DfsphConstants& k, const NeighborLists& nbrs, double dt, double maxError,
                            int maxIterations, Fluid& f, DfsphWorkspace& w) {
  const size_t n = f.size();
  if (n == 0) return {};
  resizeForParticles(w.change, n), resizeForParticles(w.error, n);
  const float rho0 = float(k.rho0), step = float(dt), perDt = float(kRelaxation / dt);
  return iterate(
      k, nbrs, dt, maxError, kMinDivergenceIterations, maxIterations, f, w,
      [&](size_t i) {
        const float rate = f.rho[i] < rho0 ? 0.0f : std::max(densityRate(nbrs, f, w, i), 0.0f);
        w.error[i] = step * rate;
        w.change[i] = rate * w.alpha[i] * perDt;
      },
      [] {});
}

}  // namespace scour
