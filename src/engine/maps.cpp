#include "engine/maps.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

bool isErosionMap(const std::string& name) {
  const std::vector<std::string>& names = erosionMapNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

TerrainMap erosionMap(const World& w, const std::string& name) {
  if (name == "wear" || name == "deposition") {
    const bool worn = name == "wear";
    TerrainMap m{name, "m", std::string(worn ? "depth eroded" : "depth deposited") + " since the start (the settled terrain)", w.heightChange(), {}};
    for (double& dh : m.values) dh = std::max(0.0, worn ? -dh : dh);
    return m;
  }
  if (name == "sediment") {
    TerrainMap m{name, "m", "sediment suspended in the water above, as a depth of soil, now", suspendedAtVertices(w), {}};
    const std::vector<double>& area = w.vertexArea();
    for (size_t v = 0; v < area.size(); ++v) m.values[v] /= area[v];
    return m;
  }
  // What the flow record holds (flow_record.h), over the bed time it covers.
  const FlowRecord& r = w.flowRecord();
  if (name == "flow") return {name, "m³/m", "near-bed water that passed over, per unit width, over the run", r.flow(), {}};
  if (name == "shear_peak") return {name, "Pa", "largest bed shear stress τ of eq. (9) over the run", r.shearPeak(), {}};
  if (name == "wetness") {
    TerrainMap m{name, "-", "fraction of the run's bed time with water within h above", r.wetTime(), {}};
    for (double& wet : m.values) wet = r.time() > 0 ? wet / r.time() : 0.0;
    return m;
  }
  if (name == "shear_mean") {
    TerrainMap m{name, "Pa", "mean bed shear stress τ over the time it was wet", r.shearIntegral(), {}};
    const std::vector<double> wet = r.wetTime();
    for (size_t v = 0; v < wet.size(); ++v) m.values[v] = wet[v] > 0 ? m.values[v] / wet[v] : 0.0;
    return m;
  }
  if (name == "flow_direction") {
    TerrainMap m{name, "-", "mean near-bed flow direction over the run, a unit vector (x, z)", r.flowX(), r.flowZ()};
    for (size_t v = 0; v < m.values.size(); ++v) {
      const double len = std::hypot(m.values[v], m.second[v]);
      m.values[v] = len > 0 ? m.values[v] / len : 0.0;
      m.second[v] = len > 0 ? m.second[v] / len : 0.0;
    }
    return m;
  }
  throw std::invalid_argument("no erosion map called '" + name + "'");
}

std::vector<TerrainMap> erosionMaps(const World& w, const std::vector<std::string>& names) {
  std::vector<TerrainMap> maps;
  for (const std::string& n : names) maps.push_back(erosionMap(w, n));
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
