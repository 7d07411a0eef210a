#include "scene/presets.h"

#include <cmath>
#include <stdexcept>

namespace scour {

const std::vector<PresetInfo>& presetList() {
  static const std::vector<PresetInfo> list = {
      {"default", "water released down a sloping valley, with a source feeding it"},
      {"dambreak", "Martin & Moyce (1952) dam break: a 2.25 in × 4.5 in water column released"},
      {"hydrostatic", "a tank of still water, for the hydrostatic pressure profile"},
      {"slope", "a block of water sliding down an inclined valley (no source)"},
      {"block", "a wide pool of water over a gently rolling heightfield (benchmark)"},
      {"settling", "sediment-only: a frozen lattice of water, sediment settling from one top particle (Fig. 4)"},
      {"diffusion", "sediment-only: a frozen lattice of water, sediment diffusing from the centre (Fig. 5)"},
  };
  return list;
}

void fillBlock(Scene& s, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const double ds = s.desc.params.spacing;
  Eigen::Vector3i n = ((hi - lo) / ds).array().round().cast<int>();
  const double top = lo.y() + n.y() * ds, rhoG = s.desc.params.rest_density * s.desc.params.gravity;
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        Eigen::Vector3d x = lo + ds * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
        s.desc.particles.push_back(x.cast<float>());
        s.desc.pressure.push_back(float(rhoG * (top - x.y())));  // at rest: hydrostatic
      }
  s.water_blocks.emplace_back(lo, hi);
}

namespace {

Heightfield flat(double lx, double lz, double cell) {
  int nx = std::max(2, int(std::round(lx / cell)) + 1), nz = std::max(2, int(std::round(lz / cell)) + 1);
  return Heightfield(nx, nz, lx / (nx - 1), lz / (nz - 1));
}

Scene dambreak(double scale) {
  // Martin & Moyce's column: width a = 2.25 in, height 2a, against the tank's left wall (x = 0),
  // flowing along +x over a dry floor. The tank is 10a long; the slab is a few particles deep in z
  // (the experiment is two-dimensional), held by walls.
  const double a = 0.05715;
  Scene s;
  s.name = "dambreak";
  s.description = presetList()[1].description;
  int n = std::max(4, int(std::round(16 * std::cbrt(scale))));
  SimParams& p = s.desc.params;
  p.spacing = a / n;
  p.sound_speed = 20.0;  // > 10 × √(2 g · 2a) ≈ 15 m/s
  p.viscosity = 5e-4;
  double depth = 6 * p.spacing;
  s.desc.terrain = flat(10 * a, depth, a / 4);
  s.terrain_kind = "flat";
  fillBlock(s, {0, 0, 0}, {a, 2 * a, depth});
  return s;
}

Scene hydrostatic(double scale) {
  Scene s;
  s.name = "hydrostatic";
  s.description = presetList()[2].description;
  SimParams& p = s.desc.params;
  const double H = 0.4;
  p.spacing = 0.02 / std::cbrt(scale);
  p.sound_speed = 10.0 * std::sqrt(2.0 * p.gravity * H);
  p.viscosity = 5e-3;  // damps the start-up pressure waves so the column comes to rest
  s.desc.terrain = flat(0.2, 0.2, 0.05);
  s.terrain_kind = "flat";
  fillBlock(s, {0, 0, 0}, {0.2, H, 0.2});
  return s;
}

// An inclined valley: falls along +x at the given slope, with a parabolic cross-section in z.
Heightfield valley(double lx, double lz, double cell, double slope, double sideRise) {
  Heightfield hf = flat(lx, lz, cell);
  for (int k = 0; k < hf.nz(); ++k)
    for (int i = 0; i < hf.nx(); ++i) {
      double x = i * hf.dx(), z = k * hf.dz() - 0.5 * lz;
      hf.at(i, k) = slope * (lx - x) + sideRise * (2 * z / lz) * (2 * z / lz);
    }
  return hf;
}

Scene slope(double scale, bool withSource) {
  Scene s;
  s.name = withSource ? "default" : "slope";
  s.description = presetList()[withSource ? 0 : 3].description;
  SimParams& p = s.desc.params;
  p.spacing = 0.02 / std::cbrt(scale);
  p.sound_speed = 30.0;
  p.viscosity = 1e-3;
  p.boundary_friction = 1e-4;
  s.desc.effects.no_slip = true;
  const double lx = 2.0, lz = 0.8, slopeRatio = 0.35;
  s.desc.terrain = valley(lx, lz, 0.04, slopeRatio, 0.15);
  s.terrain_kind = "valley";
  // Water block resting on the upper end, lifted to clear the terrain under it.
  double top = slopeRatio * lx + 0.15;
  fillBlock(s, {0.02, top - 0.14, 0.2}, {0.32, top + 0.16, 0.6});
  if (withSource) {
    Source src;
    src.center = {0.1, top + 0.3, 0.4};
    src.radius = 0.05;
    src.direction = {1, -0.3, 0};
    src.rate = 0.002;
    s.desc.sources.push_back(src);
    // The river: it erodes, carries, settles and deposits; a sink takes the water (and what it
    // carries) out at the lower end.
    Effects& e = s.desc.effects;
    e.erosion = e.settling = e.diffusion = e.deposition = true;
    p.diffusion = 0.01;  // strongly mixed would be 0.1 (paper); this keeps Δt at the SPH limit
    Sink sink;
    sink.lo = {lx - 0.15, -1.0, -1.0};
    sink.hi = {lx + 1.0, 2.0, 2.0};
    s.desc.sinks.push_back(sink);
  }
  return s;
}

Scene block(double scale, long particles) {
  // A pool Δs-deep layers thick over a gently rolling floor, sized to the requested count; the
  // default is the paper's Canyon count (136,000).
  Scene s;
  s.name = "block";
  s.description = presetList()[4].description;
  SimParams& p = s.desc.params;
  p.spacing = 0.05;
  p.sound_speed = 20.0;
  p.viscosity = 1e-3;
  p.boundary_friction = 1e-5;
  s.desc.effects.no_slip = true;  // so the bench times the boundary particles too
  long target = particles > 0 ? particles : long(136000 * scale);
  const int layers = 16;
  double side = std::sqrt(double(target) / layers) * p.spacing;
  Heightfield hf = flat(side, side, 2 * p.spacing);
  for (int k = 0; k < hf.nz(); ++k)
    for (int i = 0; i < hf.nx(); ++i)
      hf.at(i, k) = 0.02 * std::sin(6.28 * i * hf.dx() / side * 3) * std::cos(6.28 * k * hf.dz() / side * 2);
  s.desc.terrain = std::move(hf);
  s.terrain_kind = "rolling";
  int per = int(std::round(side / p.spacing));
  double w = per * p.spacing;
  fillBlock(s, {0, 0.03, 0}, {w, 0.03 + layers * p.spacing, w});
  return s;
}

// A frozen lattice (the paper's Figures 4 and 5): fluid motion off, only the sediment passes run.
Scene sedimentLattice(const std::string& name, int nx, int ny, int nz, bool settle) {
  Scene s;
  s.name = name;
  s.description = settle ? presetList()[5].description : presetList()[6].description;
  SimParams& p = s.desc.params;
  p.spacing = 0.1;
  p.max_dt = 0.01;
  s.desc.effects.fluid_motion = false;
  s.desc.effects.settling = settle;
  s.desc.effects.diffusion = !settle;
  const double ds = p.spacing;
  s.desc.terrain = flat(nx * ds, nz * ds, ds);
  s.terrain_kind = "flat";
  fillBlock(s, {0, 0, 0}, {nx * ds, ny * ds, nz * ds});
  s.desc.concentration.assign(s.desc.particles.size(), 0.0);
  // The marked particle: top centre (settling) or centre (diffusion).
  const int mi = nx / 2, mk = nz / 2, mj = settle ? ny - 1 : ny / 2;
  s.desc.concentration[size_t(mk) * nx * ny + size_t(mj) * nx + mi] = settle ? 0.05 : 0.5;
  return s;
}

}  // namespace

Scene makePreset(const std::string& name, double scale, long particles) {
  if (!(scale > 0) || !std::isfinite(scale)) throw std::invalid_argument("--scale must be a positive number");
  if (name == "dambreak") return dambreak(scale);
  if (name == "hydrostatic") return hydrostatic(scale);
  if (name == "slope") return slope(scale, false);
  if (name == "default") return slope(scale, true);
  if (name == "block") return block(scale, particles);
  if (name == "settling") return sedimentLattice(name, 9, 40, 9, true);
  if (name == "diffusion") return sedimentLattice(name, 21, 21, 21, false);
  std::string names;
  for (const auto& p : presetList()) names += std::string(names.empty() ? "" : ", ") + p.name;
  throw std::invalid_argument("unknown scene '" + name + "' (built-in scenes: " + names + ")");
}

}  // namespace scour
