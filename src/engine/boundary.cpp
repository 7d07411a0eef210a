#include "engine/boundary.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <omp.h>

#include "engine/parallel.h"

namespace scour {

BoundarySampler::BoundarySampler(const Heightfield& hf, double spacing, BoundarySampling sampling)
    : spacing_(spacing),
      block_(sampling == BoundarySampling::kSpacing ? blockCells(hf, spacing) : 0),
      tilesX_((hf.nx() - 2) / kTileCells + 1),
      tilesZ_((hf.nz() - 2) / kTileCells + 1) {}

bool BoundarySampler::updateActiveTiles(const Heightfield& hf, const std::vector<Vec3f>& fluid,
                                        double reach) {
  const double tw = kTileCells * hf.dx(), td = kTileCells * hf.dz();
  auto tileX = [&](double x) { return std::clamp(int(std::floor((x - hf.x0()) / tw)), 0, tilesX_ - 1); };
  auto tileZ = [&](double z) { return std::clamp(int(std::floor((z - hf.z0()) / td)), 0, tilesZ_ - 1); };
  const size_t n = fluid.size();
  std::vector<int> now;
  // Each thread marks its own copy; a tile is active when any copy marks it (the same set at any
  // thread count).
#pragma omp parallel
  {
    const int threads = omp_get_num_threads();
#pragma omp single
    mark_.assign(size_t(threads) * size_t(tilesX_) * tilesZ_, 0);
    uint8_t* mine = mark_.data() + size_t(omp_get_thread_num()) * tilesX_ * tilesZ_;
#pragma omp for schedule(static)
    for (size_t j = 0; j < n; ++j) {
      const Vec3f& p = fluid[j];
      if (p.y() - hf.heightAt(p.x(), p.z()) > reach) continue;
      const int ia = tileX(p.x() - reach), ib = tileX(p.x() + reach);
      const int ka = tileZ(p.z() - reach), kb = tileZ(p.z() + reach);
      for (int k = ka; k <= kb; ++k)
        for (int i = ia; i <= ib; ++i) mine[size_t(k) * tilesX_ + i] = 1;
    }
#pragma omp single
    {
      const size_t tiles = size_t(tilesX_) * tilesZ_;
      for (size_t t = 0; t < tiles; ++t)
        for (size_t c = 0; c < size_t(threads); ++c)
          if (mark_[c * tiles + t]) {
            now.push_back(int(t));
            break;
          }
    }
  }
  bool changed = now != active_;
  active_.swap(now);
  return changed;
}

int BoundarySampler::blockCells(const Heightfield& hf, double spacing) {
  const double r = spacing / std::max(hf.dx(), hf.dz());
  // Two particles per cell (one per triangle) against one per block: whichever density is nearer
  // one per Δs² (equally far, in ratio, at Δs / cell = 2^(−1/4)).
  if (r <= std::pow(2.0, -0.25)) return 0;
  // b × b cells to a block, b the whole number whose density 1 / (b cells)² is nearest one per Δs²
  // in ratio, as above: b + 1 once r passes √(b (b + 1)) (at Δs / cell = 1.49, blocks of 2 cells
  // give 0.55 particles per Δs², single cells 2.2).
  long b = std::max(1L, long(std::floor(r)));
  if (r * r > double(b) * double(b + 1)) ++b;
  return int(std::clamp(b, 1L, long(kTileCells)));
}

int BoundarySampler::tileOf(int triangle, int cellsX) const {
  const int cell = triangle / 2;
  return (cell / cellsX / kTileCells) * tilesX_ + (cell % cellsX) / kTileCells;
}

void BoundarySampler::generate(const Heightfield& hf, BoundaryParticles& b) const {
  const int cellsX = hf.nx() - 1, cellsZ = hf.nz() - 1;
  BoundaryParticles out;
  out.cellsX = cellsX;
  // The set changes by a few tiles a step: room for the last one and an eighth more (pushing
  // alone would double the arrays, and their slack is memory every particle pays for).
  out.reserve(b.size() + b.size() / 8 + 64);
  size_t j = 0;  // b's particles are in tile order: a cursor over them
  for (int t : active_) {
    while (j < b.size() && tileOf(b.triangle[j], cellsX) < t) ++j;
    if (j < b.size() && tileOf(b.triangle[j], cellsX) == t) {
      // A tile that stays active keeps its particles (they have followed the terrain).
      const size_t first = j;
      while (j < b.size() && tileOf(b.triangle[j], cellsX) == t) ++j;
      out.append(b, first, j);
      continue;
    }
    int ti = t % tilesX_, tk = t / tilesX_;
    const int iEnd = std::min(cellsX, (ti + 1) * kTileCells), kEnd = std::min(cellsZ, (tk + 1) * kTileCells);
    if (block_ == 0) {
      sampleCells(hf, ti * kTileCells, tk * kTileCells, iEnd, kEnd, spacing_, out);
      continue;
    }
    for (int k = tk * kTileCells; k < kEnd; k += block_)
      for (int i = ti * kTileCells; i < iEnd; i += block_)
        sampleBlock(hf, i, k, std::min(block_, iEnd - i), std::min(block_, kEnd - k), spacing_, out);
  }
  b = std::move(out);
}

void BoundarySampler::sampleCells(const Heightfield& hf, int i0, int k0, int i1, int k1, double spacing,
                                  BoundaryParticles& out) {
  const int cellsX = hf.nx() - 1;
  for (int k = k0; k < k1; ++k)
    for (int i = i0; i < i1; ++i)
      for (int s = 0; s < 2; ++s) sampleTriangle(hf, 2 * (k * cellsX + i) + s, spacing, out);
}

void BoundarySampler::sampleBlock(const Heightfield& hf, int i0, int k0, int bx, int bz, double spacing,
                                  BoundaryParticles& out) {
  const int cellsX = hf.nx() - 1;
  double area3d = 0;
  for (int k = k0; k < k0 + bz; ++k)
    for (int i = i0; i < i0 + bx; ++i)
      for (int s = 0; s < 2; ++s) {
        auto c = hf.triangleCorners(2 * (k * cellsX + i) + s);
        area3d += 0.5 * (c[1] - c[0]).cross(c[2] - c[0]).norm();
      }
  if (std::lround(std::sqrt(area3d) / spacing) >= 2) {
    // Too steep for one particle: halve the block (a slope needs a few more particles, not one per
    // triangle); a single cell that is still too steep (a cliff) is sampled triangle by triangle.
    if (bx == 1 && bz == 1) return sampleCells(hf, i0, k0, i0 + 1, k0 + 1, spacing, out);
    const int hx = (bx + 1) / 2, hz = (bz + 1) / 2;
    for (int k : {0, hz})
      for (int i : {0, hx}) {
        const int sx = i == 0 ? hx : bx - hx, sz = k == 0 ? hz : bz - hz;
        if (sx > 0 && sz > 0) sampleBlock(hf, i0 + i, k0 + k, sx, sz, spacing, out);
      }
    return;
  }
  const double xc = hf.x0() + (i0 + 0.5 * bx) * hf.dx(), zc = hf.z0() + (k0 + 0.5 * bz) * hf.dz();
  const int tri = hf.surface(xc, zc).triangle;
  auto c = hf.triangleCorners(tri);
  // (u, w) of the centre in the triangle, in x–z; the height as follow() computes it.
  const Eigen::Vector3d ab = c[1] - c[0], ac = c[2] - c[0];
  const double det = ab.x() * ac.z() - ab.z() * ac.x();
  const double px = xc - c[0].x(), pz = zc - c[0].z();
  const float u = float((px * ac.z() - pz * ac.x()) / det), w = float((ab.x() * pz - ab.z() * px) / det);
  out.x.emplace_back(float(xc), float(c[0].y() + u * ab.y() + w * ac.y()), float(zc));
  out.triangle.push_back(tri);
  out.area.push_back(bx * hf.dx() * bz * hf.dz());
  out.bary.emplace_back(u, w);
  out.patch.push_back(k0 * cellsX + i0);
  out.extent.push_back(uint8_t(bx | bz << 4));
}

void BoundarySampler::follow(const Heightfield& hf, const std::vector<uint32_t>& vertexMarks,
                             uint32_t epoch, BoundaryParticles& b) {
  const size_t n = b.size();
#pragma omp parallel for schedule(static) if (n >= kParallelFrom)
  for (size_t k = 0; k < n; ++k) {
    bool moved = false;
    for (size_t v : hf.triangleVertexIndices(b.triangle[k])) moved = moved || vertexMarks[v] == epoch;
    if (!moved) continue;
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
    out.patch.push_back(-1);
    out.extent.push_back(0);
  };
  // Row j of the scanline walk: the upward sub-triangles, then the downward ones between them.
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i + j < n; ++i) put(i + 1.0 / 3.0, j + 1.0 / 3.0);
    for (int i = 0; i + j < n - 1; ++i) put(i + 2.0 / 3.0, j + 2.0 / 3.0);
  }
}

}  // namespace scour
