#include "engine/frame.h"

#include "engine/maps.h"
#include "engine/world.h"

namespace scour {

Frame makeFrame(const World& w, const std::string& map) {
  Frame f;
  f.step = w.steps();
  f.time = w.time();
  const Fluid& fl = w.fluid();
  f.position = fl.x;
  f.concentration.resize(fl.size());
  f.speed.resize(fl.size());
  for (size_t i = 0; i < fl.size(); ++i) {
    f.concentration[i] = float(w.concentration(i));
    f.speed[i] = fl.v[i].norm();
  }
  const SimParams& p = w.params();
  f.spacing = float(p.spacing);
  f.support = float(p.support());
  f.mass = float(p.particleMass());
  f.rest_density = float(p.rest_density);
  const Heightfield hf = w.settledTerrain();
  f.nx = hf.nx(), f.nz = hf.nz();
  f.dx = hf.dx(), f.dz = hf.dz(), f.x0 = hf.x0(), f.z0 = hf.z0();
  f.height.assign(hf.heights().begin(), hf.heights().end());
  const std::vector<double>& h0 = w.initialTerrain().heights();
  f.change.resize(h0.size());
  for (size_t i = 0; i < h0.size(); ++i) f.change[i] = float(hf.heights()[i] - h0[i]);
  if (map.empty()) return f;
  const TerrainMap m = erosionMap(w, map);
  f.mapName = m.name;
  f.map.assign(m.values.begin(), m.values.end());
  f.map2.assign(m.second.begin(), m.second.end());
  return f;
}

}  // namespace scour
