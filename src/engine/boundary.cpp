#include "engine/boundary.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace scour {

BoundarySampler::BoundarySampler(const Heightfield& hf, double spacing)
    : spacing_(spacing),
      tilesX_((hf.nx() - 2) / kTileCells + 1),
      tilesZ_((hf.nz() - 2) / kTileCells + 1),
      mark_(size_t(tilesX_) * tilesZ_, 0) {}

bool BoundarySampler::updateActiveTiles(const Heightfield& hf, const std::vector<Vec3f>& fluid,
                                        double reach) {
  std::fill(mark_.begin(), mark_.end(), 0);
  const double tw = kTileCells * hf.dx(), td = kTileCells * hf.dz();
  auto tileX = [&](double x) { return std::clamp(int(std::floor((x - hf.x0()) / tw)), 0, tilesX_ - 1); };
  auto tileZ = [&](double z) { return std::clamp(int(std::floor((z - hf.z0()) / td)), 0, tilesZ_ - 1); };
  for (const Vec3f& p : fluid) {
    if (p.y() - hf.heightAt(p.x(), p.z()) > reach) continue;
    int ia = tileX(p.x() - reach), ib = tileX(p.x() + reach);
    int ka = tileZ(p.z() - reach), kb = tileZ(p.z() + reach);
    for (int k = ka; k <= kb; ++k)
      for (int i = ia; i <= ib; ++i) mark_[size_t(k) * tilesX_ + i] = 1;
  }
  std::vector<int> now;
  for (int t = 0; t < int(mark_.size()); ++t)
    if (mark_[t]) now.push_back(t);
  bool changed = now != active_;
  active_.swap(now);
  return changed;
}

void BoundarySampler::generate(const Heightfield& hf, BoundaryParticles& out) const {
  out.x.clear();
  out.triangle.clear();
  out.area.clear();
  out.bary.clear();
  const int cellsX = hf.nx() - 1, cellsZ = hf.nz() - 1;
  for (int t : active_) {
    int ti = t % tilesX_, tk = t / tilesX_;
    for (int k = tk * kTileCells; k < std::min(cellsZ, (tk + 1) * kTileCells); ++k)
      for (int i = ti * kTileCells; i < std::min(cellsX, (ti + 1) * kTileCells); ++i)
        for (int s = 0; s < 2; ++s) sampleTriangle(hf, 2 * (k * cellsX + i) + s, spacing_, out);
  }
}

void BoundarySampler::follow(const Heightfield& hf, const std::vector<int>& triangles,
                             BoundaryParticles& b) {
  if (triangles.empty()) return;
  std::vector<uint8_t> moved(size_t(hf.triangleCount()), 0);
  for (int t : triangles) moved[size_t(t)] = 1;
  const size_t n = b.size();
#pragma omp parallel for schedule(static)
  for (size_t k = 0; k < n; ++k) {
    if (!moved[size_t(b.triangle[k])]) continue;
    auto c = hf.triangleCorners(b.triangle[k]);
    const double u = b.bary[k].x(), w = b.bary[k].y();
    b.x[k].y() = float(c[0].y() + u * (c[1].y() - c[0].y()) + w * (c[2].y() - c[0].y()));
  }
}

void BoundarySampler::sampleTriangle(const Heightfield& hf, int tri, double spacing,
                                     BoundaryParticles& out) {
  auto c = hf.triangleCorners(tri);
  const Eigen::Vector3d ab = c[1] - c[0], ac = c[2] - c[0];
  // n² particles for a surface area A: about one per Δs², as a lattice of spacing Δs would have.
  const double area3d = 0.5 * ab.cross(ac).norm();
  const int n = std::max(1, int(std::lround(std::sqrt(area3d) / spacing)));
  // Projected (x–z) area: the heightfield's cell area is what the terrain volume is made of.
  double projected = 0.5 * std::abs(ab.x() * ac.z() - ab.z() * ac.x());
  double each = projected / (double(n) * n);
  auto put = [&](double u, double w) {
    Eigen::Vector3d p = c[0] + (u / n) * ab + (w / n) * ac;
    out.x.push_back(p.cast<float>());
    out.triangle.push_back(tri);
    out.area.push_back(each);
    out.bary.emplace_back(float(u / n), float(w / n));
  };
  // Row j of the scanline walk: the upward sub-triangles, then the downward ones between them.
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i + j < n; ++i) put(i + 1.0 / 3.0, j + 1.0 / 3.0);
    for (int i = 0; i + j < n - 1; ++i) put(i + 2.0 / 3.0, j + 2.0 / 3.0);
  }
}

}  // namespace scour
