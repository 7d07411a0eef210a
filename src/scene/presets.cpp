#include "scene/presets.h"

#include <stb_image.h>

#include <cmath>
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
  };
  return list;
}

namespace {

// A greyscale image as doubles, row-major (rows along +z).
struct Gray {
  int w = 0, h = 0;
  std::vector<double> v;
};

Gray readHeightmap(const TerrainSpec& t) {
  Gray g;
  const std::string& f = t.file;
  const bool raw = f.size() > 4 && f.substr(f.size() - 4) == ".r32";
  constexpr long long kMaxPixels = 1LL << 27;  // 134 M pixels: 1 GB of doubles
  if (raw) {
    if (t.raw_width < 2 || t.raw_height < 2)
      throw TerrainError(f + ": a .r32 heightmap needs terrain.raw_width and raw_height ≥ 2");
    if (1LL * t.raw_width * t.raw_height > kMaxPixels)
      throw TerrainError(f + ": " + std::to_string(t.raw_width) + " × " +
                         std::to_string(t.raw_height) + " pixels is more than this build reads");
    std::ifstream in(f, std::ios::binary);
    if (!in) throw TerrainError(f + ": cannot open the heightmap");
    std::vector<float> px(size_t(t.raw_width) * t.raw_height);
    in.read(reinterpret_cast<char*>(px.data()), std::streamsize(px.size() * sizeof(float)));
    if (in.gcount() != std::streamsize(px.size() * sizeof(float)))
      throw TerrainError(f + ": holds fewer than raw_width × raw_height float32 values");
    g.w = t.raw_width, g.h = t.raw_height;
    g.v.assign(px.begin(), px.end());
  } else {
    int w = 0, h = 0, comp = 0;
    if (!stbi_info(f.c_str(), &w, &h, &comp)) {
      std::ifstream probe(f);
      throw TerrainError(f + (probe ? ": not a readable image (" + std::string(stbi_failure_reason()) + ")"
                                    : ": cannot open the heightmap"));
    }
    if (comp != 1)
      throw TerrainError(f + ": expected a greyscale image, found " + std::to_string(comp) +
                         " channels");
    if (1LL * w * h > kMaxPixels)
      throw TerrainError(f + ": " + std::to_string(w) + " × " + std::to_string(h) +
                         " pixels is more than this build reads");
    g.w = w, g.h = h;
    g.v.resize(size_t(w) * h);
    if (stbi_is_16_bit(f.c_str())) {
      stbi_us* px = stbi_load_16(f.c_str(), &w, &h, &comp, 1);
      if (!px) throw TerrainError(f + ": cannot decode: " + stbi_failure_reason());
      for (size_t i = 0; i < g.v.size(); ++i) g.v[i] = px[i];
      stbi_image_free(px);
    } else {
      stbi_uc* px = stbi_load(f.c_str(), &w, &h, &comp, 1);
      if (!px) throw TerrainError(f + ": cannot decode: " + stbi_failure_reason());
      for (size_t i = 0; i < g.v.size(); ++i) g.v[i] = px[i];
      stbi_image_free(px);
    }
  }
  for (double x : g.v)
    if (!std::isfinite(x)) throw TerrainError(f + ": holds a non-finite height");
  return g;
}

void fillFromHeightmap(const TerrainSpec& t, Heightfield& hf) {
  const Gray g = readHeightmap(t);
  const int cw = t.crop_w > 0 ? t.crop_w : g.w - t.crop_x, ch = t.crop_h > 0 ? t.crop_h : g.h - t.crop_z;
  if (t.crop_x < 0 || t.crop_z < 0 || cw < 2 || ch < 2 || t.crop_x + cw > g.w || t.crop_z + ch > g.h)
    throw TerrainError(t.file + ": the crop [" + std::to_string(t.crop_x) + ", " +
                       std::to_string(t.crop_z) + ", " + std::to_string(cw) + ", " +
                       std::to_string(ch) + "] does not fit the " + std::to_string(g.w) + " × " +
                       std::to_string(g.h) + " image");
  // Bilinear resampling of the crop onto the grid.
  for (int k = 0; k < hf.nz(); ++k)
    for (int i = 0; i < hf.nx(); ++i) {
      const double u = double(i) / (hf.nx() - 1) * (cw - 1), w = double(k) / (hf.nz() - 1) * (ch - 1);
      const int i0 = std::min(int(u), cw - 2), k0 = std::min(int(w), ch - 2);
      const double fu = u - i0, fw = w - k0;
      auto at = [&](int a, int b) { return g.v[size_t(t.crop_z + k0 + b) * g.w + t.crop_x + i0 + a]; };
      hf.at(i, k) = (1 - fw) * ((1 - fu) * at(0, 0) + fu * at(1, 0)) + fw * ((1 - fu) * at(0, 1) + fu * at(1, 1));
    }
  // Scale to the range the scene asks for.
  const double lo = hf.minHeight(), hi = hf.maxHeight(), span = hi > lo ? hi - lo : 1.0;
  for (double& h : hf.heights()) h = t.height_min + (h - lo) / span * (t.height_max - t.height_min);
}

}  // namespace

Heightfield buildTerrain(const TerrainSpec& t) {
  const int nx = std::max(2, int(std::round(t.length_x / t.cell)) + 1);
  const int nz = std::max(2, int(std::round(t.length_z / t.cell)) + 1);
  Heightfield hf(nx, nz, t.length_x / (nx - 1), t.length_z / (nz - 1));
  if (t.kind == "heightmap") {
    fillFromHeightmap(t, hf);
    for (double& h : hf.heights()) h += t.base;
    return hf;
  }
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const double x = i * hf.dx(), z = k * hf.dz();
      double h = t.base;
      if (t.kind == "valley") {
        // Falls along +x; parabolic cross-section in z, lowest on the axis z = length_z / 2.
        const double across = 2.0 * (z - 0.5 * t.length_z) / t.length_z;
        h += t.slope * (t.length_x - x) + t.side_rise * across * across;
      } else if (t.kind == "rolling") {
        h += t.amplitude * std::sin(2 * M_PI * 3 * x / t.length_x) *
             std::cos(2 * M_PI * 2 * z / t.length_z);
      }
      hf.at(i, k) = h;
    }
  return hf;
}

Scene buildScene(const SceneSpec& spec) {
  Scene s;
  s.spec = spec;
  WorldDesc& d = s.desc;
  d.params = spec.params;
  d.terrain = buildTerrain(spec.terrain);
  d.domain = spec.domain;
  d.effects = spec.effects;
  d.sources = spec.sources;
  d.sinks = spec.sinks;
  const double ds = spec.params.spacing;
  const double rhoG = spec.params.rest_density * spec.params.gravity;
  for (const WaterBlock& b : spec.blocks) {
    // Whole cells that fit in the box (never more, so no particle starts inside a wall next to
    // it), centred in it.
    const Eigen::Vector3d extent = b.max - b.min;
    const Eigen::Vector3i n = (extent / ds + Eigen::Vector3d::Constant(1e-6)).array().floor().cast<int>();
    const Eigen::Vector3d lo = b.min + 0.5 * (extent - ds * n.cast<double>());
    const double top = lo.y() + n.y() * ds;
    for (int k = 0; k < n.z(); ++k)
      for (int j = 0; j < n.y(); ++j)
        for (int i = 0; i < n.x(); ++i) {
          Eigen::Vector3d x = lo + ds * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
          d.particles.push_back(x.cast<float>());
          d.pressure.push_back(float(rhoG * (top - x.y())));  // at rest: hydrostatic
        }
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
  // Martin & Moyce's column: width a = 2.25 in, height 2a, against the tank's left wall (x = 0),
  // flowing along +x over a dry floor. The tank is 10a long; the slab is six particles deep in z
  // (the experiment is two-dimensional), held by walls.
  const double a = 0.05715;
  SceneSpec s = named("dambreak");
  SimParams& p = s.params;
  const int n = std::max(4, int(std::round(16 * std::cbrt(scale))));
  p.spacing = a / n;
  p.sound_speed = 20.0;  // > 10 × √(2 g · 2a) ≈ 15 m/s
  p.viscosity = 5e-4;
  const double depth = 6 * p.spacing;
  s.terrain = flatTerrain(10 * a, depth, a / 4);
  s.blocks.push_back({{0, 0, 0}, {a, 2 * a, depth}});
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
  // Water resting on the upper end, lifted to clear the terrain under it.
  const double top = s.terrain.slope * lx + s.terrain.side_rise;
  s.blocks.push_back({{0.02, top - 0.14, 0.2}, {0.32, top + 0.16, 0.6}});
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
  std::string names;
  for (const auto& p : presetList()) names += std::string(names.empty() ? "" : ", ") + p.name;
  throw std::invalid_argument("unknown scene '" + name + "' (built-in scenes: " + names + ")");
}

}  // namespace scour
