#include "scene/presets.h"

#include "scene/builtin_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace scour {

namespace {

size_t nearestVertex(const Heightfield& hf, double x, double z) {
  const int i = std::clamp(int(std::lround((x - hf.x0()) / hf.dx())), 0, hf.nx() - 1);
  const int k = std::clamp(int(std::lround((z - hf.z0()) / hf.dz())), 0, hf.nz() - 1);
  return size_t(k) * hf.nx() + i;
}

// The vertices below the block's top, inside its (x, z) box, connected (4-neighbour) to the
// vertex nearest flood_from.
std::vector<uint8_t> floodedVertices(const Heightfield& hf, const WaterBlock& b) {
  std::vector<uint8_t> wet(size_t(hf.nx()) * hf.nz(), 0);
  auto open = [&](int i, int k) {
    const double x = hf.x0() + i * hf.dx(), z = hf.z0() + k * hf.dz();
    return x >= b.min.x() && x <= b.max.x() && z >= b.min.z() && z <= b.max.z() &&
           hf.at(i, k) < b.max.y();
  };
  const size_t seed = nearestVertex(hf, b.flood_from.x(), b.flood_from.y());
  std::vector<size_t> stack;
  if (open(int(seed % hf.nx()), int(seed / hf.nx()))) stack.push_back(seed), wet[seed] = 1;
  while (!stack.empty()) {
    const size_t v = stack.back();
    stack.pop_back();
    const int i = int(v % hf.nx()), k = int(v / hf.nx());
    const int di[4] = {1, -1, 0, 0}, dk[4] = {0, 0, 1, -1};
    for (int n = 0; n < 4; ++n) {
      const int a = i + di[n], c = k + dk[n];
      if (a < 0 || c < 0 || a >= hf.nx() || c >= hf.nz()) continue;
      const size_t u = size_t(c) * hf.nx() + a;
      if (!wet[u] && open(a, c)) wet[u] = 1, stack.push_back(u);
    }
  }
  return wet;
}

}  // namespace

Eigen::Vector3d blockLattice(const WaterBlock& b, double spacing) {
  return ((b.max - b.min) / spacing + Eigen::Vector3d::Constant(1e-6)).array().floor();
}

Scene buildScene(const SceneSpec& spec) {
  Scene s;
  s.spec = spec;
  WorldDesc& d = s.desc;
  checkFootprint(spec);
  d.params = spec.params;
  d.terrain = buildTerrain(spec.terrain);
  checkFootprint(spec, &d.terrain);
  checkGeometry(spec, d.terrain);
  d.domain = spec.domain;
  d.effects = spec.effects;
  d.sources = spec.sources;
  d.sinks = spec.sinks;
  d.rain = spec.rain;
  const double ds = spec.params.spacing;
  const double rhoG = spec.params.rest_density * spec.params.gravity;
  for (size_t blockIndex = 0; blockIndex < spec.blocks.size(); ++blockIndex) {
    const WaterBlock& b = spec.blocks[blockIndex];
    const std::string at = "water.blocks[" + std::to_string(blockIndex) + "]";
    const size_t before = d.particles.size();
    long buried = 0;
    const std::vector<uint8_t> wet = b.flood ? floodedVertices(d.terrain, b) : std::vector<uint8_t>{};
    // Whole cells that fit in the box (never more, so no particle starts inside a wall next to
    // it), centred in it.
    const Eigen::Vector3d extent = b.max - b.min;
    const Eigen::Vector3i n = blockLattice(b, ds).cast<int>();  // checkFootprint bounded it
    const Eigen::Vector3d lo = b.min + 0.5 * (extent - ds * n.cast<double>());
    const double top = lo.y() + n.y() * ds;
    for (int k = 0; k < n.z(); ++k)
      for (int j = 0; j < n.y(); ++j)
        for (int i = 0; i < n.x(); ++i) {
          Eigen::Vector3d x = lo + ds * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
          const double ground = d.terrain.heightAt(x.x(), x.z());
          if ((b.above_terrain || b.flood) && x.y() < ground + 0.5 * ds) continue;
          // A plain block must not reach into the terrain: its particles would start inside it.
          if (x.y() < ground) ++buried;
          if (b.flood && !wet[nearestVertex(d.terrain, x.x(), x.z())]) continue;
          d.particles.push_back(x.cast<float>());
          d.pressure.push_back(float(rhoG * (top - x.y())));  // at rest: hydrostatic
        }
    if (buried > 0)
      throw SceneError(at + ": " + std::to_string(buried) + " of its lattice points lie inside the terrain: raise "
                       "the block, or fill only above the terrain (above_terrain: true)");
    if (d.particles.size() == before)
      throw SceneError(at + ": fills no particle at spacing " + std::to_string(ds) + " m" +
                       (b.flood ? " (the terrain at flood_from is not below the block's top)"
                        : b.above_terrain ? " (the terrain is not below the block's top)"
                                          : " (the block is thinner than Δs)"));
  }
  if (!spec.sediment.empty()) {
    d.concentration.assign(d.particles.size(), 0.0);
    for (const SedimentMark& m : spec.sediment) {
      size_t best = 0;
      double bestD = std::numeric_limits<double>::max();
      for (size_t i = 0; i < d.particles.size(); ++i) {
        double dist = (d.particles[i].cast<double>() - m.position).squaredNorm();
        if (dist < bestD) bestD = dist, best = i;
      }
      if (!d.particles.empty()) d.concentration[best] = m.c;
    }
  }
  return s;
}

const std::vector<PresetInfo>& presetList() {
  static const std::vector<PresetInfo> list = [] {
    std::vector<PresetInfo> out;
    for (const BuiltinScene& b : builtinScenes())
      if (!b.stress) out.push_back({b.spec.name.c_str(), b.spec.description.c_str()});
    return out;
  }();
  return list;
}

void applyScaling(SceneSpec& s, double scale, long particles) {
  if (!(scale > 0) || !std::isfinite(scale))
    throw std::invalid_argument("--scale must be a positive number");
  const Scaling& c = s.scaling;
  SimParams& p = s.params;
  switch (c.rule) {
    case Scaling::Rule::kSpacing: p.spacing /= std::cbrt(scale); break;
    case Scaling::Rule::kFixed: break;
    case Scaling::Rule::kColumn: {
      const int n = std::max(4, int(std::round(c.cells * std::cbrt(scale))));
      p.spacing = c.width / n;
      const double depth = c.slab_cells * p.spacing;
      s.terrain.length_z = depth;
      for (WaterBlock& b : s.blocks) b.max.z() = depth;
      break;
    }
    case Scaling::Rule::kPool: {
      const double target = particles > 0 ? double(particles) : double(long(c.particles * scale));
      const int per = std::max(2, int(std::round(std::sqrt(target / c.layers))));
      const double side = per * p.spacing;
      s.terrain.length_x = s.terrain.length_z = side;
      for (WaterBlock& b : s.blocks) {
        b.max.x() = b.min.x() + side, b.max.z() = b.min.z() + side;
        b.max.y() = b.min.y() + c.layers * p.spacing;
      }
      break;
    }
  }
}

SceneSpec presetSpec(const std::string& name, double scale, long particles) {
  const BuiltinScene* b = findBuiltinScene(name);
  if (!b) {
    // A near miss gets its nearest built-in name ("canyn": canyon), a far one only the list.
    std::vector<std::string> names;
    for (const BuiltinScene& k : builtinScenes()) names.push_back(k.spec.name);
    const std::string best = nearestName(name, names, slipDistance(name));
    const std::string hint = best.empty() ? std::string() : "; did you mean '" + best + "'?";
    throw std::invalid_argument("unknown scene '" + name + "'" + hint + " (built-in scenes: " +
                                builtinSceneNames() + ")");
  }
  SceneSpec s = b->spec;
  applyScaling(s, scale, particles);
  return s;
}

}  // namespace scour
