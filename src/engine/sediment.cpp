#include "engine/sediment.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace scour {

SedimentConstants::SedimentConstants(const SimParams& p)
    : volume(p.particleVolume()),
      c_max(p.c_max),
      rz(p.rz_exponent),
      vs0(p.settlingSpeed()),
      diffusion(p.diffusion),
      k_eps(p.k_eps),
      tau_c(p.tau_c),
      shear_k(p.shear_k),
      shear_n(p.shear_n),
      rho_s(p.sediment_density),
      min_distance(0.1 * p.support()),
      spline(p.support()) {}

double SedimentConstants::hindrance(double c) const {
  if (c >= c_max) return 0.0;
  return 1.0 - std::pow(std::max(c, 0.0) / c_max, rz);
}

namespace {

// The raw volume flux [m³/s] from donor d to acceptor a, for a pair at distance r whose vertical
// separation is dy = y_d − y_a. Both particles of a pair call it with the same arguments, so the
// two sides agree to the bit.
struct PairFlux {
  const SedimentConstants& k;
  bool settle, diffuse;
  double operator()(double cd, double ca, double dy, double r) const {
    if (r <= 0.0) return 0.0;
    const double absF = -k.spline.F(r);
    double flux = 0.0;
    // Eq. (16), doubled (model.md): the donor above gives along v_s = −|v_s| ŷ at the acceptor's
    // hindered speed; |v_s · r̂| = |v_s| dy / r.
    if (settle && dy > 0.0 && cd > 0.0)
      flux += 2.0 * k.volume * k.volume * cd * k.vs0 * k.hindrance(ca) * (dy / r) * absF;
    // Model.md's eq. (19): V_a V_d 2D (C_d − C_a) |F| / r, from the richer to the poorer.
    if (diffuse && cd > ca) flux += k.volume * k.volume * 2.0 * k.diffusion * (cd - ca) * absF / r;
    return flux;
  }
};

// Eq. (20) with the doubled eq. (16) flux: donor fluid particle above a boundary particle.
double depositFlux(const SedimentConstants& k, double cd, double dy, double r) {
  if (r <= 0.0 || dy <= 0.0 || cd <= 0.0) return 0.0;
  return 2.0 * k.volume * k.volume * cd * k.vs0 * k.hindrance(0.0) * (dy / r) * (-k.spline.F(r));
}

}  // namespace

void transferSediment(const SedimentConstants& k, const SedimentEffects& fx,
                      const NeighborLists& nbrs, const NeighborLists& bnbrs,
                      const BoundaryParticles& b, double dt, Fluid& f, TerrainAccumulator& acc) {
  const size_t n = f.size();
  const double V = k.volume, room = k.c_max * V;
  const PairFlux pair{k, fx.settling, fx.diffusion};
  const bool deposit = fx.deposition && bnbrs.size() == n;
  std::vector<double> outScale(n, 1.0), inScale(n, 1.0), delta(n, 0.0);

  // Pass 1: each particle's raw outflow (to fluid and to the terrain) and inflow over Δt.
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    const double ci = f.sed[i] / V;
    double out = 0.0, in = 0.0;
    const uint32_t* js = nbrs.begin(i);
    for (uint32_t c = 0; c < nbrs.count(i); ++c) {
      const uint32_t j = js[c];
      const double cj = f.sed[j] / V;
      if (ci == 0.0 && cj == 0.0) continue;
      const double dy = double(f.x[i].y()) - double(f.x[j].y());
      const double r = double((f.x[i] - f.x[j]).norm());
      out += pair(ci, cj, dy, r);
      in += pair(cj, ci, -dy, r);
    }
    if (deposit && ci > 0.0) {
      forEachNeighbor(bnbrs, f.x, b.x, i, [&](uint32_t bj, const Vec3f& xib, float r) {
        (void)bj;
        out += depositFlux(k, ci, double(xib.y()), double(r));
      });
    }
    out *= dt;
    in *= dt;
    if (out > f.sed[i]) outScale[i] = f.sed[i] / out;
    const double space = std::max(room - f.sed[i], 0.0);
    if (in > space) inScale[i] = space / in;
  }

  // Pass 2: apply each directed flux scaled by min(donor's out-scale, acceptor's in-scale).
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    const double ci = f.sed[i] / V;
    double d = 0.0;
    const uint32_t* js = nbrs.begin(i);
    for (uint32_t c = 0; c < nbrs.count(i); ++c) {
      const uint32_t j = js[c];
      const double cj = f.sed[j] / V;
      if (ci == 0.0 && cj == 0.0) continue;
      const double dy = double(f.x[i].y()) - double(f.x[j].y());
      const double r = double((f.x[i] - f.x[j]).norm());
      d += pair(cj, ci, -dy, r) * dt * std::min(outScale[j], inScale[i]);
      d -= pair(ci, cj, dy, r) * dt * std::min(outScale[i], inScale[j]);
    }
    if (deposit && ci > 0.0) {
      forEachNeighbor(bnbrs, f.x, b.x, i, [&](uint32_t, const Vec3f& xib, float r) {
        d -= depositFlux(k, ci, double(xib.y()), double(r)) * dt * outScale[i];
      });
    }
    delta[i] = d;
  }

  // The terrain's side of the deposits, in particle order (deterministic).
  if (deposit) {
    for (size_t i = 0; i < n; ++i) {
      const double ci = f.sed[i] / V;
      if (ci <= 0.0) continue;
      forEachNeighbor(bnbrs, f.x, b.x, i, [&](uint32_t bj, const Vec3f& xib, float r) {
        double v = depositFlux(k, ci, double(xib.y()), double(r)) * dt * outScale[i];
        if (v > 0.0) acc.add(b.triangle[bj], v);
      });
    }
  }
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) f.sed[i] = std::clamp(f.sed[i] + delta[i], 0.0, room);
}

void erode(const SedimentConstants& k, const NeighborLists& bnbrs, const BoundaryParticles& b,
           double dt, Fluid& f, TerrainAccumulator& acc) {
  const size_t n = f.size();
  const double room = k.c_max * k.volume;
  std::vector<double> scale(n, 0.0);
  auto pairVolume = [&](double speed, double l, double area) {
    // Eqs. (9)–(10): θ = v_rel / l, τ = K θⁿ, ε = K_ε (τ − τ_c) for τ > τ_c; mass L_b² ε Δt.
    const double theta = speed / std::max(l, k.min_distance);
    const double tau = k.shear_k * std::pow(theta, k.shear_n);
    if (tau <= k.tau_c) return 0.0;
    return area * k.k_eps * (tau - k.tau_c) * dt / k.rho_s;
  };
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    if (bnbrs.count(i) == 0) continue;
    const double speed = double(f.v[i].norm());
    double total = 0.0;
    forEachNeighbor(bnbrs, f.x, b.x, i, [&](uint32_t bj, const Vec3f&, float r) {
      total += pairVolume(speed, double(r), b.area[bj]);
    });
    if (total <= 0.0) continue;
    const double space = std::max(room - f.sed[i], 0.0);
    scale[i] = total > space ? space / total : 1.0;  // model.md: C_j ≤ C_max
  }
  // Both sides in particle order: the fluid particle gains exactly the sum the terrain loses.
  for (size_t i = 0; i < n; ++i) {
    if (scale[i] == 0.0) continue;
    const double speed = double(f.v[i].norm());
    double gained = 0.0;
    forEachNeighbor(bnbrs, f.x, b.x, i, [&](uint32_t bj, const Vec3f&, float r) {
      double v = pairVolume(speed, double(r), b.area[bj]) * scale[i];
      if (v <= 0.0) return;
      acc.add(b.triangle[bj], -v);
      gained += v;
    });
    f.sed[i] += gained;
  }
}

std::vector<double> vertexAreas(const Heightfield& hf) {
  std::vector<double> a(hf.heights().size(), 0.0);
  const double third = hf.dx() * hf.dz() / 2.0 / 3.0;
  for (int t = 0; t < hf.triangleCount(); ++t)
    for (auto [i, k] : hf.triangleVertices(t)) a[size_t(k) * hf.nx() + i] += third;
  return a;
}

double terrainVolume(const Heightfield& hf, const std::vector<double>& areas, double reference) {
  double v = 0.0;
  const auto& h = hf.heights();
  for (size_t i = 0; i < h.size(); ++i) v += (h[i] - reference) * areas[i];
  return v;
}

void depositOnTriangle(Heightfield& hf, const std::vector<double>& areas, int tri, double volume) {
  if (volume == 0.0) return;
  auto verts = hf.triangleVertices(tri);
  std::array<size_t, 3> idx;
  for (int a = 0; a < 3; ++a) idx[a] = size_t(verts[a][1]) * hf.nx() + verts[a][0];
  auto& h = hf.heights();
  const double sign = volume > 0 ? 1.0 : -1.0;
  double left = std::abs(volume);
  // Order from the lowest (deposit) or highest (erosion) vertex; ties by index, deterministically.
  std::sort(idx.begin(), idx.end(), [&](size_t p, size_t q) {
    double hp = sign * h[p], hq = sign * h[q];
    return hp < hq || (hp == hq && p < q);
  });
  // Work in "sign-flipped" heights g = sign·h so both cases fill the lowest first.
  double areaSum = 0.0;
  for (int level = 0; level < 3; ++level) {
    areaSum += areas[idx[level]];
    const double g = sign * h[idx[level]];
    const double next = level < 2 ? sign * h[idx[level + 1]] : INFINITY;
    const double cost = (next - g) * areaSum;
    if (left <= cost || level == 2) {
      const double rise = left / areaSum;
      for (int a = 0; a <= level; ++a) h[idx[a]] = sign * (g + rise);
      return;
    }
    left -= cost;
    for (int a = 0; a <= level; ++a) h[idx[a]] = sign * next;
  }
}

std::vector<int> applyTerrainChange(Heightfield& hf, const std::vector<double>& areas,
                                    TerrainAccumulator& acc) {
  std::vector<int> tris = acc.touched;
  std::sort(tris.begin(), tris.end());
  std::vector<int> moved;
  for (int t : tris) {
    depositOnTriangle(hf, areas, t, acc.volume[size_t(t)]);
    acc.volume[size_t(t)] = 0.0;
    // Every triangle sharing a vertex of t may have moved: the cells around t's cell.
    const int cells = hf.nx() - 1, cell = t / 2, ci = cell % cells, ck = cell / cells;
    for (int k = std::max(ck - 1, 0); k <= std::min(ck + 1, hf.nz() - 2); ++k)
      for (int i = std::max(ci - 1, 0); i <= std::min(ci + 1, cells - 1); ++i)
        for (int s = 0; s < 2; ++s) moved.push_back(2 * (k * cells + i) + s);
  }
  acc.touched.clear();
  std::sort(moved.begin(), moved.end());
  moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
  return moved;
}

}  // namespace scour
