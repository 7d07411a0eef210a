#include "engine/heightfield.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/parallel.h"

namespace scour {

Heightfield::Heightfield(int nx, int nz, double dx, double dz, double x0, double z0)
    : nx_(nx), nz_(nz), dx_(dx), dz_(dz), x0_(x0), z0_(z0), h_(size_t(nx) * nz, 0.0) {}

double Heightfield::minHeight() const { return *std::min_element(h_.begin(), h_.end()); }
double Heightfield::maxHeight() const { return *std::max_element(h_.begin(), h_.end()); }

double pointTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double den = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * den) + ac * (vc * den))).norm();
}

double Heightfield::distanceToSurface(const Eigen::Vector3d& p) const {
  const int ci = std::clamp(int(std::floor((p.x() - x0_) / dx_)), 0, nx_ - 2);
  const int ck = std::clamp(int(std::floor((p.z() - z0_) / dz_)), 0, nz_ - 2);
  double best = std::numeric_limits<double>::infinity();
  for (int k = std::max(ck - 1, 0); k <= std::min(ck + 1, nz_ - 2); ++k)
    for (int i = std::max(ci - 1, 0); i <= std::min(ci + 1, nx_ - 2); ++i)
      for (int t = 0; t < 2; ++t)
        best = std::min(best, distanceToTriangle(2 * (k * (nx_ - 1) + i) + t, p));
  return best;
}

std::array<std::array<int, 2>, 3> Heightfield::triangleVertices(int tri) const {
  int cell = tri / 2, t = tri % 2;
  int i = cell % (nx_ - 1), k = cell / (nx_ - 1);
  if (t == 0) return {{{i, k}, {i + 1, k}, {i + 1, k + 1}}};
  return {{{i, k}, {i + 1, k + 1}, {i, k + 1}}};
}

std::array<Eigen::Vector3d, 3> Heightfield::triangleCorners(int tri) const {
  auto v = triangleVertices(tri);
  std::array<Eigen::Vector3d, 3> c;
  for (int a = 0; a < 3; ++a)
    c[a] = {x0_ + dx_ * v[a][0], at(v[a][0], v[a][1]), z0_ + dz_ * v[a][1]};
  return c;
}

WallSurface::WallSurface(const Heightfield& terrain, double radius) {
  const int rx = int(std::floor(radius / terrain.dx() + 1e-9));
  const int rz = int(std::floor(radius / terrain.dz() + 1e-9));
  if (rx < 1 && rz < 1) return;  // no vertex but the centre within the radius: the terrain itself
  for (int b = -rz; b <= rz; ++b)
    for (int a = -rx; a <= rx; ++a) {
      const double u = rx ? double(a) / rx : 0.0, w = rz ? double(b) / rz : 0.0;
      if (u * u + w * w <= 1.0 + 1e-9) disk_.push_back({a, b});
    }
  highest_ = smooth_ = terrain;
  mark_.assign(terrain.heights().size(), 0);
  for (int k = 0; k < terrain.nz(); ++k)
    for (int i = 0; i < terrain.nx(); ++i) highest_.at(i, k) = filtered(terrain, i, k, true);
  for (int k = 0; k < terrain.nz(); ++k)
    for (int i = 0; i < terrain.nx(); ++i) smooth_.at(i, k) = filtered(highest_, i, k, false);
}

double WallSurface::filtered(const Heightfield& in, int i, int k, bool highest) const {
  double m = highest ? -std::numeric_limits<double>::infinity() : 0.0;
  for (const auto& o : disk_) {
    const double v =
        in.at(std::clamp(i + o[0], 0, in.nx() - 1), std::clamp(k + o[1], 0, in.nz() - 1));
    m = highest ? std::max(m, v) : m + v;
  }
  return highest ? m : m / double(disk_.size());
}

std::vector<int> WallSurface::spread(const Heightfield& t, const std::vector<int>& vertices) {
  if (++epoch_ == 0) std::fill(mark_.begin(), mark_.end(), 0u), epoch_ = 1;
  std::vector<int> out;
  for (int v : vertices) {
    const int i = v % t.nx(), k = v / t.nx();
    for (const auto& o : disk_) {
      const int ii = i + o[0], kk = k + o[1];
      if (ii < 0 || kk < 0 || ii >= t.nx() || kk >= t.nz()) continue;
      const int u = kk * t.nx() + ii;
      if (mark_[size_t(u)] != epoch_) mark_[size_t(u)] = epoch_, out.push_back(u);
    }
  }
  return out;
}

void WallSurface::follow(const Heightfield& terrain, const std::vector<int>& movedVertices) {
  if (disk_.empty() || movedVertices.empty()) return;
  // A vertex's maximum reads the terrain within the radius, its average the maxima within it.
  // Each vertex is written once from what the pass before wrote: in parallel once a pass reads
  // kParallelFrom heights (its vertices times the disk's), and the same at any thread count.
  const std::vector<int> maxima = spread(terrain, movedVertices);
  const long nm = long(maxima.size());
#pragma omp parallel for schedule(static) if (maxima.size() * disk_.size() >= kParallelFrom)
  for (long m = 0; m < nm; ++m) {
    const int u = maxima[size_t(m)];
    highest_.heights()[size_t(u)] = filtered(terrain, u % terrain.nx(), u / terrain.nx(), true);
  }
  const std::vector<int> means = spread(terrain, maxima);
  const long ns = long(means.size());
#pragma omp parallel for schedule(static) if (means.size() * disk_.size() >= kParallelFrom)
  for (long m = 0; m < ns; ++m) {
    const int u = means[size_t(m)];
    smooth_.heights()[size_t(u)] = filtered(highest_, u % terrain.nx(), u / terrain.nx(), false);
  }
}

}  // namespace scour
