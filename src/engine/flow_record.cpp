#include "engine/flow_record.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace scour {

namespace {
constexpr int kTileVertices = FlowRecord::kTile * FlowRecord::kTile;
}

void FlowRecord::reset(int nx, int nz) {
  nx_ = nx, nz_ = nz, tilesX_ = (nx + kTile - 1) / kTile;
  time_ = 0;
  slot_.assign(size_t(tilesX_) * size_t((nz + kTile - 1) / kTile), -1);
  tiles_.clear(), values_.clear();
}

size_t FlowRecord::slotOf(size_t tile) {
  if (slot_[tile] < 0) {
    slot_[tile] = int32_t(tiles_.size());
    tiles_.push_back(int(tile));
    // Grown as reserveWithSlack grows them: the record's memory follows the wetted area.
    reserveWithSlack(values_, values_.size() + size_t(kFields) * kTileVertices);
    values_.resize(values_.size() + size_t(kFields) * kTileVertices, 0.0);
  }
  return size_t(slot_[tile]);
}

void FlowRecord::record(const Heightfield& hf, const std::vector<double>& vertexArea, const Fluid& f,
                        const std::vector<float>& tau, double volume, double spacing, double dtm) {
  if (nx_ != hf.nx() || nz_ != hf.nz()) reset(hf.nx(), hf.nz());
  const size_t n = f.size();
  const double half = 0.5 * spacing, invDx = 1.0 / hf.dx(), invDz = 1.0 / hf.dz();
  // Each near-bed particle's footprint (one written per particle: any thread count).
  resizeForParticles(foot_, n);
#pragma omp parallel for schedule(static)
  for (size_t p = 0; p < n; ++p) {
    Footprint& ft = foot_[p];
    if (!(tau[p] >= 0.0f)) {
      ft = {1, 0, 1, 0};  // empty: not near the bed
      continue;
    }
    const double x = double(f.x[p].x()) - hf.x0(), z = double(f.x[p].z()) - hf.z0();
    // The footprint's vertices; the nearest one when none lies inside it.
    int i0 = int(std::ceil((x - half) * invDx)), i1 = int(std::floor((x + half) * invDx));
    int k0 = int(std::ceil((z - half) * invDz)), k1 = int(std::floor((z + half) * invDz));
    i0 = std::max(i0, 0), k0 = std::max(k0, 0), i1 = std::min(i1, nx_ - 1), k1 = std::min(k1, nz_ - 1);
    if (i0 > i1 || k0 > k1) {
      i0 = i1 = std::clamp(int(std::lround(x * invDx)), 0, nx_ - 1);
      k0 = k1 = std::clamp(int(std::lround(z * invDz)), 0, nz_ - 1);
    }
    ft = {i0, i1, k0, k1};
  }
  // The tiles made in the order the particles first touch them (the state keeps that order), and
  // each touched tile's particles listed in index order: a counting sort over the slots.
  auto eachTile = [&](const Footprint& ft, auto&& visit) {
    for (int tk = ft.k0 / kTile; tk <= ft.k1 / kTile; ++tk)
      for (int ti = ft.i0 / kTile; ti <= ft.i1 / kTile; ++ti) visit(size_t(tk) * size_t(tilesX_) + size_t(ti));
  };
  start_.assign(tiles_.size() + 1, 0);
  for (size_t p = 0; p < n; ++p)
    if (foot_[p].i0 <= foot_[p].i1)
      eachTile(foot_[p], [&](size_t tile) {
        const size_t s = slotOf(tile);
        if (s + 1 >= start_.size()) start_.resize(s + 2, 0);
        ++start_[s + 1];
      });
  for (size_t s = 1; s < start_.size(); ++s) start_[s] += start_[s - 1];
  reserveWithSlack(member_, start_.back());
  member_.resize(start_.back());
  {
    std::vector<uint32_t> cursor(start_.begin(), start_.end() - 1);
    for (size_t p = 0; p < n; ++p)
      if (foot_[p].i0 <= foot_[p].i1)
        eachTile(foot_[p], [&](size_t tile) { member_[cursor[size_t(slot_[tile])]++] = uint32_t(p); });
  }
  // Each touched tile summed by one thread, its particles in index order: every vertex's sums are
  // the same, bit for bit, at any thread count.
  const ptrdiff_t slots = ptrdiff_t(start_.size()) - 1;
#pragma omp parallel for schedule(dynamic, 4)
  for (ptrdiff_t s = 0; s < slots; ++s) {
    if (start_[size_t(s)] == start_[size_t(s) + 1]) continue;
    const int ti = tiles_[size_t(s)] % tilesX_, tk = tiles_[size_t(s)] / tilesX_;
    const int ia = ti * kTile, ka = tk * kTile;
    double qxSum[kTileVertices] = {}, qzSum[kTileVertices] = {};
    float tauMax[kTileVertices] = {};
    bool wet[kTileVertices] = {};
    for (uint32_t e = start_[size_t(s)]; e < start_[size_t(s) + 1]; ++e) {
      const size_t p = member_[e];
      const Footprint& ft = foot_[p];
      double area = 0;
      for (int k = ft.k0; k <= ft.k1; ++k)
        for (int i = ft.i0; i <= ft.i1; ++i) area += vertexArea[size_t(k) * size_t(nx_) + size_t(i)];
      const double qx = volume * double(f.v[p].x()) / area, qz = volume * double(f.v[p].z()) / area;
      const float t = tau[p];
      const int i0 = std::max(ft.i0, ia), i1 = std::min(ft.i1, ia + kTile - 1);
      const int k0 = std::max(ft.k0, ka), k1 = std::min(ft.k1, ka + kTile - 1);
      for (int k = k0; k <= k1; ++k)
        for (int i = i0; i <= i1; ++i) {
          const int v = (k - ka) * kTile + (i - ia);
          qxSum[v] += qx, qzSum[v] += qz;
          tauMax[v] = std::max(tauMax[v], t);
          wet[v] = true;
        }
    }
    double* at = values_.data() + size_t(s) * kFields * kTileVertices;
    for (int v = 0; v < kTileVertices; ++v) {
      if (!wet[v]) continue;
      auto field = [&](Field fl) -> double& { return at[size_t(fl) * kTileVertices + size_t(v)]; };
      field(Field::kWet) += dtm;
      field(Field::kFlow) += std::sqrt(qxSum[v] * qxSum[v] + qzSum[v] * qzSum[v]) * dtm;
      field(Field::kQx) += qxSum[v] * dtm;
      field(Field::kQz) += qzSum[v] * dtm;
      field(Field::kShear) += double(tauMax[v]) * dtm;
      field(Field::kPeak) = std::max(field(Field::kPeak), double(tauMax[v]));
    }
  }
  time_ += dtm;
}

std::vector<double> FlowRecord::dense(Field fl) const {
  std::vector<double> out(size_t(nx_) * size_t(nz_), 0.0);
  for (size_t slot = 0; slot < tiles_.size(); ++slot) {
    const int ti = tiles_[slot] % tilesX_, tk = tiles_[slot] / tilesX_;
    const double* at = values_.data() + (slot * kFields + size_t(fl)) * kTileVertices;
    for (int a = 0; a < kTile; ++a)
      for (int b = 0; b < kTile; ++b) {
        const int i = ti * kTile + b, k = tk * kTile + a;
        if (i < nx_ && k < nz_) out[size_t(k) * size_t(nx_) + size_t(i)] = at[a * kTile + b];
      }
  }
  return out;
}

size_t FlowRecord::bytes() const {
  return slot_.capacity() * sizeof(int32_t) + tiles_.capacity() * sizeof(int) + values_.capacity() * sizeof(double) +
         foot_.capacity() * sizeof(Footprint) + start_.capacity() * sizeof(uint32_t) +
         member_.capacity() * sizeof(uint32_t);
}

void FlowRecord::restore(int nx, int nz, double time, std::vector<int> tiles, std::vector<double> values,
                         int tile) {
  FlowRecord r;
  r.reset(nx, nz);
  auto corrupt = [] { return std::runtime_error("state is corrupt (flow maps)"); };
  if (tile != kTile) {
    // Tiles of `tile` vertices (a multiple of ours) cut into ours, in the same order; one that
    // holds only zeros (never touched) is left out, as a run would never have made it.
    const int per = tile / kTile, tilesXOld = (nx + tile - 1) / tile;
    const size_t oldVertices = size_t(tile) * size_t(tile);
    if (tile % kTile != 0 || values.size() != tiles.size() * size_t(kFields) * oldVertices) throw corrupt();
    std::vector<int> cutTiles;
    std::vector<double> cutValues;
    for (size_t slot = 0; slot < tiles.size(); ++slot) {
      if (tiles[slot] < 0 || tiles[slot] >= tilesXOld * ((nz + tile - 1) / tile)) throw corrupt();
      const int ti = tiles[slot] % tilesXOld, tk = tiles[slot] / tilesXOld;
      for (int a = 0; a < per; ++a)
        for (int b = 0; b < per; ++b) {
          const int i0 = (ti * per + b) * kTile, k0 = (tk * per + a) * kTile;
          if (i0 >= nx || k0 >= nz) continue;
          const size_t at = cutValues.size();
          bool any = false;
          for (int fl = 0; fl < kFields; ++fl)
            for (int v = 0; v < kTileVertices; ++v) {
              const size_t row = size_t(a * kTile + v / kTile), col = size_t(b * kTile + v % kTile);
              cutValues.push_back(values[(slot * kFields + size_t(fl)) * oldVertices + row * size_t(tile) + col]);
              any = any || cutValues.back() != 0.0;
            }
          if (any) cutTiles.push_back((k0 / kTile) * r.tilesX_ + i0 / kTile);
          else cutValues.resize(at);
        }
    }
    tiles = std::move(cutTiles), values = std::move(cutValues);
  }
  if (!std::isfinite(time) || time < 0 || values.size() != tiles.size() * size_t(kFields) * kTileVertices) throw corrupt();
  for (size_t slot = 0; slot < tiles.size(); ++slot) {
    const int t = tiles[slot];
    if (t < 0 || size_t(t) >= r.slot_.size() || r.slot_[size_t(t)] >= 0) throw corrupt();
    r.slot_[size_t(t)] = int32_t(slot);
  }
  for (size_t e = 0; e < values.size(); ++e) {
    const auto fl = Field(e / kTileVertices % kFields);
    const bool signedField = fl == Field::kQx || fl == Field::kQz;
    if (!std::isfinite(values[e]) || (!signedField && values[e] < 0)) throw corrupt();
  }
  r.time_ = time;
  r.tiles_ = std::move(tiles), r.values_ = std::move(values);
  *this = std::move(r);
}

}  // namespace scour
