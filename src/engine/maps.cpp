#include "engine/maps.h"

#include <algorithm>
#include <cmath>

#include "engine/world.h"

namespace scour {

const std::vector<std::string>& erosionMapNames() {
  static const std::vector<std::string> names = {"wear",       "deposition", "sediment",      "flow",
                                                 "wetness",    "shear_peak", "shear_mean",    "flow_direction"};
  return names;
}

namespace {

// Each particle's sediment volume over the terrain's grid, by bilinear weights [m³ per vertex].
std::vector<double> suspendedAtVertices(const World& w) {
  const Heightfield& hf = w.terrain();
  const int nx = hf.nx(), nz = hf.nz();
  std::vector<double> at(size_t(nx) * nz, 0.0);
  const Fluid& f = w.fluid();
  for (size_t i = 0; i < f.size(); ++i) {
    const double s = f.sed[i];
    if (s == 0.0) continue;
    const double u = std::clamp((double(f.x[i].x()) - hf.x0()) / hf.dx(), 0.0, double(nx - 1));
    const double q = std::clamp((double(f.x[i].z()) - hf.z0()) / hf.dz(), 0.0, double(nz - 1));
    const int i0 = std::min(int(u), nx - 2), k0 = std::min(int(q), nz - 2);
    const double fu = u - i0, fq = q - k0;
    const size_t v = size_t(k0) * nx + i0;
    at[v] += s * (1 - fu) * (1 - fq);
    at[v + 1] += s * fu * (1 - fq);
    at[v + nx] += s * (1 - fu) * fq;
    at[v + nx + 1] += s * fu * fq;
  }
  return at;
}

}  // namespace

std::vector<TerrainMap> erosionMaps(const World& w) {
  const std::vector<double> dh = w.heightChange();
  const std::vector<double>& area = w.vertexArea();
  TerrainMap wear{"wear", "m", "depth eroded since the start (the settled terrain)", {}, {}};
  TerrainMap deposition{"deposition", "m", "depth deposited since the start (the settled terrain)", {}, {}};
  TerrainMap sediment{"sediment", "m", "sediment suspended in the water above, as a depth of soil, now", {}, {}};
  wear.values.resize(dh.size()), deposition.values.resize(dh.size());
  for (size_t v = 0; v < dh.size(); ++v) {
    wear.values[v] = std::max(0.0, -dh[v]);
    deposition.values[v] = std::max(0.0, dh[v]);
  }
  sediment.values = suspendedAtVertices(w);
  for (size_t v = 0; v < area.size(); ++v) sediment.values[v] /= area[v];
  // What the flow record holds (flow_record.h), over the bed time it covers.
  const FlowRecord& r = w.flowRecord();
  TerrainMap flow{"flow", "m³/m", "near-bed water that passed over, per unit width, over the run", r.flow(), {}};
  TerrainMap wetness{"wetness", "-", "fraction of the run's bed time with water within h above", r.wetTime(), {}};
  TerrainMap peak{"shear_peak", "Pa", "largest bed shear stress τ of eq. (9) over the run", r.shearPeak(), {}};
  TerrainMap mean{"shear_mean", "Pa", "mean bed shear stress τ over the time it was wet", r.shearIntegral(), {}};
  TerrainMap direction{"flow_direction", "-", "mean near-bed flow direction over the run, a unit vector (x, z)", r.flowX(), {}};
  direction.second = r.flowZ();
  for (size_t v = 0; v < dh.size(); ++v) {
    const double wet = wetness.values[v];
    wetness.values[v] = r.time() > 0 ? wet / r.time() : 0.0;
    mean.values[v] = wet > 0 ? mean.values[v] / wet : 0.0;
    const double len = std::hypot(direction.values[v], direction.second[v]);
    direction.values[v] = len > 0 ? direction.values[v] / len : 0.0;
    direction.second[v] = len > 0 ? direction.second[v] / len : 0.0;
  }
  std::vector<TerrainMap> maps;
  for (TerrainMap* m : {&wear, &deposition, &sediment, &flow, &wetness, &peak, &mean, &direction}) maps.push_back(std::move(*m));
  return maps;
}

std::vector<double> resampleGrid(const std::vector<double>& v, int nx, int nz, int nx2, int nz2) {
  std::vector<double> out(size_t(nx2) * nz2);
  for (int k = 0; k < nz2; ++k)
    for (int i = 0; i < nx2; ++i) {
      const double u = nx2 > 1 ? double(i) * (nx - 1) / (nx2 - 1) : 0.0;
      const double q = nz2 > 1 ? double(k) * (nz - 1) / (nz2 - 1) : 0.0;
      const int i0 = std::min(int(u), nx - 2), k0 = std::min(int(q), nz - 2);
      const double fu = u - i0, fq = q - k0;
      auto at = [&](int a, int b) { return v[size_t(k0 + b) * nx + i0 + a]; };
      out[size_t(k) * nx2 + i] =
          (1 - fq) * ((1 - fu) * at(0, 0) + fu * at(1, 0)) + fq * ((1 - fu) * at(0, 1) + fu * at(1, 1));
    }
  return out;
}

}  // namespace scour
