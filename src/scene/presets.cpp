#include "scene/presets.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace scour {

const std::vector<PresetInfo>& presetList() {
  static const std::vector<PresetInfo> list = {
      {"default", "a river down a sloping valley, fed by a source: it erodes, carries and deposits"},
      {"dambreak", "Martin & Moyce (1952) dam break: a 2.25 in × 4.5 in water column released"},
      {"hydrostatic", "a tank of still water, for the hydrostatic pressure profile"},
      {"slope", "a block of water sliding down an inclined valley (no source, no erosion)"},
      {"block", "a wide pool of water over a gently rolling heightfield (benchmark)"},
      {"settling", "sediment-only: a frozen lattice of water, sediment settling from one top particle (Fig. 4)"},
      {"diffusion", "sediment-only: a frozen lattice of water, sediment diffusing from the centre (Fig. 5)"},
      {"canyon", "paper Fig. 1: a river carving the real Grand Canyon (SRTM, 700 x 350 grid, ~130k particles)"},
      {"lake", "paper Fig. 7: a lake in a crater fills until it overflows and cuts new paths (~90k particles)"},
      {"waterfall", "paper Fig. 8: two sources over three terraces carve waterfalls (728 x 512 grid, ~650k particles)"},
      {"rain", "rain on rolling fBm hills: rills gather into streams that run off the edges"},
  };
  return list;
}

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

void damBreakTank(SceneSpec& s, double a, double spacing, double tank) {
  s.params.spacing = spacing;
  const double depth = 6 * spacing;
  s.terrain = flatTerrain(tank, depth, a / 4);
  s.blocks.push_back({{0, 0, 0}, {a, 2 * a, depth}});
}

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

namespace {

SceneSpec named(const std::string& name) {
  SceneSpec s;
  s.name = name;
  for (const auto& p : presetList())
    if (name == p.name) s.description = p.description;
  return s;
}

SceneSpec dambreak(double scale) {
  // Martin & Moyce's column: width a = 2.25 in, in a tank 10a long.
  const double a = 0.05715;
  SceneSpec s = named("dambreak");
  SimParams& p = s.params;
  const int n = std::max(4, int(std::round(16 * std::cbrt(scale))));
  damBreakTank(s, a, a / n, 10 * a);
  p.sound_speed = 20.0;  // > 10 × √(2 g · 2a) ≈ 15 m/s
  p.viscosity = 5e-4;
  return s;
}

SceneSpec hydrostatic(double scale) {
  SceneSpec s = named("hydrostatic");
  SimParams& p = s.params;
  const double H = 0.4;
  p.spacing = 0.02 / std::cbrt(scale);
  p.sound_speed = 10.0 * std::sqrt(2.0 * p.gravity * H);
  p.viscosity = 5e-3;  // damps the start-up pressure waves so the column comes to rest
  s.terrain = flatTerrain(0.2, 0.2, 0.05);
  s.blocks.push_back({{0, 0, 0}, {0.2, H, 0.2}});
  return s;
}

SceneSpec slope(double scale, bool river) {
  SceneSpec s = named(river ? "default" : "slope");
  SimParams& p = s.params;
  p.spacing = 0.02 / std::cbrt(scale);
  p.sound_speed = 30.0;
  p.viscosity = 1e-3;
  p.boundary_friction = 1e-4;
  s.effects.no_slip = true;
  const double lx = 2.0, lz = 0.8;
  s.terrain.kind = "valley";
  s.terrain.length_x = lx;
  s.terrain.length_z = lz;
  s.terrain.cell = 0.04;
  s.terrain.slope = 0.35;
  s.terrain.side_rise = 0.15;
  // Water resting on the upper end, above the terrain under it.
  const double top = s.terrain.slope * lx + s.terrain.side_rise;
  s.blocks.push_back({{0.02, top - 0.14, 0.2}, {0.32, top + 0.16, 0.6}, true});
  if (river) {
    Source src;
    src.center = {0.1, top + 0.3, 0.4};
    src.radius = 0.05;
    src.direction = {1, -0.3, 0};
    src.rate = 0.002;
    s.sources.push_back(src);
    // It erodes, carries, settles and deposits; a sink takes the water (and what it carries)
    // out at the lower end.
    s.effects.erosion = s.effects.settling = s.effects.diffusion = s.effects.deposition = true;
    p.diffusion = 0.01;  // strongly mixed would be 0.1 (paper); this keeps Δt at the SPH limit
    s.sinks.push_back({{lx - 0.15, -1.0, -1.0}, {lx + 1.0, 2.0, 2.0}});
  }
  return s;
}

SceneSpec block(double scale, long particles) {
  // A pool 16 layers deep over a gently rolling floor, sized to the requested count; the
  // default is the paper's Canyon count (136,000).
  SceneSpec s = named("block");
  SimParams& p = s.params;
  p.spacing = 0.05;
  p.sound_speed = 20.0;
  p.viscosity = 1e-3;
  p.boundary_friction = 1e-5;
  s.effects.no_slip = true;  // so the bench times the boundary particles too
  const long target = particles > 0 ? particles : long(136000 * scale);
  const int layers = 16;
  const int per = std::max(2, int(std::round(std::sqrt(double(target) / layers))));
  const double side = per * p.spacing;
  s.terrain.kind = "rolling";
  s.terrain.length_x = s.terrain.length_z = side;
  s.terrain.cell = 2 * p.spacing;
  s.terrain.amplitude = 0.02;
  s.blocks.push_back({{0, 0.03, 0}, {side, 0.03 + layers * p.spacing, side}});
  return s;
}

// A frozen lattice (the paper's Figures 4 and 5): fluid motion off, only the sediment passes run.
SceneSpec sedimentLattice(const std::string& name, int nx, int ny, int nz, bool settle) {
  SceneSpec s = named(name);
  SimParams& p = s.params;
  p.spacing = 0.1;
  p.max_dt = 0.01;
  s.effects.fluid_motion = false;
  s.effects.settling = settle;
  s.effects.diffusion = !settle;
  const double ds = p.spacing;
  s.terrain = flatTerrain(nx * ds, nz * ds, ds);
  s.blocks.push_back({{0, 0, 0}, {nx * ds, ny * ds, nz * ds}});
  // The marked particle: top centre (settling) or centre (diffusion).
  const int mj = settle ? ny - 1 : ny / 2;
  s.sediment.push_back(
      {ds * Eigen::Vector3d(nx / 2 + 0.5, mj + 0.5, nz / 2 + 0.5), settle ? 0.05 : 0.5});
  return s;
}

// What the paper's scenes share: all the erosion effects, friction at the terrain, an open domain
// that lets the water leave. Kε = 0.1 and τc = 3 are the paper's (and our defaults); D = 0.01
// keeps the diffusion limit on Δt below the SPH one (as in `default`).
SceneSpec paperScene(const std::string& name, double spacing, double scale) {
  SceneSpec s = named(name);
  SimParams& p = s.params;
  p.spacing = spacing / std::cbrt(scale);
  p.sound_speed = 15.0;
  p.viscosity = 1e-3;
  p.boundary_friction = 1e-4;
  p.diffusion = 0.01;
  s.effects.no_slip = true;
  s.effects.erosion = s.effects.settling = s.effects.diffusion = s.effects.deposition = true;
  s.domain.walls = false;
  return s;
}

SceneSpec canyon(double scale) {
  // The SRTM tile's Colorado river stretch: a 700 × 350 pixel crop (about 63 × 31 km) mapped 1:1
  // onto a 700 × 350 cell grid of 14 × 7 m, relief 1.2 m (3.5× exaggerated), tilted 0.14 m down
  // to the west (x = 0), where the river leaves. The inner gorge is filled to a level as the
  // river, and a source keeps it flowing from the east end.
  SceneSpec s = paperScene("canyon", 0.02, scale);
  TerrainSpec& t = s.terrain;
  t.kind = "heightmap";
  t.file = "builtin:srtm-grand-canyon";
  t.crop_x = 400, t.crop_z = 620, t.crop_w = 700, t.crop_h = 350;
  t.length_x = 14.0, t.length_z = 7.0, t.cell = 0.02;
  t.height_min = 0.0, t.height_max = 1.2;
  t.slope = -0.01;
  WaterBlock river;
  river.min = {0.0, -1.0, 0.0};
  river.max = {14.0, 0.136, 7.0};
  river.flood = true;
  river.flood_from = {7.0, 4.64};  // on the river, mid-way
  s.blocks.push_back(river);
  Source src;
  src.center = {13.8, 0.25, 5.72};
  src.radius = 0.06;
  src.direction = {-1, -0.5, 0};
  src.rate = 0.004;
  s.sources.push_back(src);
  return s;
}

SceneSpec lake(double scale) {
  // A crater (paraboloid inside the rim, falling outside it) with fBm relief, tilted so that its
  // rim is lowest towards +x. It starts half full; a source fills it until it spills over the low
  // point of the rim and cuts a path down the outer slope.
  SceneSpec s = paperScene("lake", 0.0225, scale);
  TerrainSpec& t = s.terrain;
  t.kind = "bowl";
  t.length_x = t.length_z = 5.0;
  t.cell = 0.025;
  t.side_rise = 0.4;
  t.rim = 0.7;
  t.slope = 0.02;
  t.noise.amplitude = 0.04;
  t.noise.feature = 1.0;
  t.noise.octaves = 5;
  t.noise.seed = 7;
  WaterBlock pool;
  pool.min = {0.0, -1.0, 0.0};
  pool.max = {5.0, 0.36, 5.0};
  pool.flood = true;
  pool.flood_from = {2.5, 2.5};
  s.blocks.push_back(pool);
  Source src;
  src.center = {1.2, 0.7, 2.5};
  src.radius = 0.08;
  src.direction = {1, -1, 0};
  src.rate = 0.02;
  s.sources.push_back(src);
  return s;
}

SceneSpec waterfall(double scale) {
  // Three terraces falling 0.4 m each along +x, with a valley cross-section and fBm relief, on a
  // 728 × 512 cell grid. A lake on the top terrace and two sources behind it feed the falls.
  SceneSpec s = paperScene("waterfall", 0.01, scale);
  TerrainSpec& t = s.terrain;
  t.kind = "terraces";
  t.length_x = 7.28, t.length_z = 5.12, t.cell = 0.01;
  t.slope = 1.2 / 7.28;
  t.levels = 3;
  t.riser = 0.12;
  t.side_rise = 0.3;
  t.noise.amplitude = 0.02;
  t.noise.feature = 0.8;
  t.noise.octaves = 4;
  t.noise.seed = 3;
  WaterBlock top;
  top.min = {0.3, 0.5, 0.3};
  top.max = {2.3, 0.945, 4.82};
  top.above_terrain = true;
  s.blocks.push_back(top);
  for (double z : {1.8, 3.3}) {
    Source src;
    src.center = {0.15, 1.35, z};
    src.radius = 0.06;
    src.direction = {1, -0.3, 0};
    src.rate = 0.01;
    s.sources.push_back(src);
  }
  return s;
}

SceneSpec rainScene(double scale) {
  SceneSpec s = paperScene("rain", 0.02, scale);
  TerrainSpec& t = s.terrain;
  t.kind = "fbm";
  t.length_x = t.length_z = 2.0;
  t.cell = 0.02;
  t.slope = 0.1;
  t.noise.amplitude = 0.12;
  t.noise.feature = 0.8;
  t.noise.octaves = 5;
  t.noise.seed = 11;
  Rain r;
  r.lo_x = r.lo_z = 0.1;
  r.hi_x = r.hi_z = 1.9;
  r.intensity_mm_h = 2000.0;  // a storm, sped up: 0.2 L/s over the 3.2 m² region
  r.drop_height = 0.15;
  s.rain.push_back(r);
  return s;
}

}  // namespace

SceneSpec presetSpec(const std::string& name, double scale, long particles) {
  if (!(scale > 0) || !std::isfinite(scale))
    throw std::invalid_argument("--scale must be a positive number");
  if (name == "dambreak") return dambreak(scale);
  if (name == "hydrostatic") return hydrostatic(scale);
  if (name == "slope") return slope(scale, false);
  if (name == "default") return slope(scale, true);
  if (name == "block") return block(scale, particles);
  if (name == "settling") return sedimentLattice(name, 9, 40, 9, true);
  if (name == "diffusion") return sedimentLattice(name, 21, 21, 21, false);
  if (name == "canyon") return canyon(scale);
  if (name == "lake") return lake(scale);
  if (name == "waterfall") return waterfall(scale);
  if (name == "rain") return rainScene(scale);
  std::string names;
  for (const auto& p : presetList()) names += std::string(names.empty() ? "" : ", ") + p.name;
  throw std::invalid_argument("unknown scene '" + name + "' (built-in scenes: " + names + ")");
}

}  // namespace scour
