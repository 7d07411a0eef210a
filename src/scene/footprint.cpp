// The scene's limits and geometry checks: everything that would make a run allocate without
// bound, loop without bound, or blow up a few steps in is refused here, before the water is made.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/limits.h"
#include "scene/presets.h"

namespace scour {

namespace {

std::string indexed(const char* list, size_t k) { return std::string(list) + "[" + std::to_string(k) + "]"; }

template <class... A>
std::string format(const char* fmt, A... a) {
  char buf[400];
  std::snprintf(buf, sizeof buf, fmt, a...);
  return buf;
}

}  // namespace

Footprint estimateFootprint(const SceneSpec& s, const Heightfield* terrain) {
  Footprint f;
  const TerrainSpec& t = s.terrain;
  const double ds = s.params.spacing;
  f.vertices = (std::max(1.0, std::round(t.length_x / t.cell)) + 1) *
               (std::max(1.0, std::round(t.length_z / t.cell)) + 1);
  for (const WaterBlock& b : s.blocks) {
    if (!b.above_terrain && !b.flood) {
      const Eigen::Vector3d n = blockLattice(b, ds);
      f.particles += n.x() * n.y() * n.z();
    } else if (terrain) {
      // Water over the terrain: each vertex's column from Δs/2 above the ground to the top,
      // over its cell (the flooded part of a flood block is at most this).
      const Heightfield& hf = *terrain;
      double volume = 0;
      for (int k = 0; k < hf.nz(); ++k)
        for (int i = 0; i < hf.nx(); ++i) {
          const double x = hf.x0() + i * hf.dx(), z = hf.z0() + k * hf.dz();
          if (x < b.min.x() || x > b.max.x() || z < b.min.z() || z > b.max.z()) continue;
          volume += std::max(0.0, b.max.y() - std::max(b.min.y(), hf.at(i, k) + 0.5 * ds)) * hf.dx() * hf.dz();
        }
      f.particles += volume / (ds * ds * ds);
    } else {
      f.unknown = true;
    }
  }
  f.bytes = footprintBytes(f.particles, f.vertices);
  return f;
}

void checkFootprint(const SceneSpec& s, const Heightfield* terrain) {
  const Footprint f = estimateFootprint(s, terrain);
  const double ds = s.params.spacing;
  if (f.vertices > Limits::kMaxTerrainVertices)
    throw SceneError(format("terrain: %.3g grid vertices (length / cell) is more than the %.3g this build allows",
                            f.vertices, Limits::kMaxTerrainVertices));
  const double capacity = particleCapacity(f.vertices);
  if (f.particles > capacity)
    throw SceneError(format("water.blocks: %.3g particles at spacing %g m (about %.3g GB with the terrain) "
                            "is more than the %.3g that the memory limit of %g GB allows",
                            f.particles, ds, f.bytes / 1e9, capacity, Limits::kMaxBytes / 1e9));
  for (size_t k = 0; k < s.sources.size(); ++k) {
    const std::string bad = checkSourceWork(s.sources[k], s.params, indexed("sources", k));
    if (!bad.empty()) throw SceneError(bad);
  }
  for (size_t k = 0; k < s.rain.size(); ++k) {
    const double area = rainArea(s.rain[k], 0.0, s.terrain.length_x, 0.0, s.terrain.length_z);
    const std::string bad = checkRainWork(s.rain[k], area, s.params, indexed("rain", k));
    if (!bad.empty()) throw SceneError(bad);
  }
}

void checkGeometry(const SceneSpec& s, const Heightfield& hf) {
  const double ds = s.params.spacing;
  // Positions are floats: far from the origin neighbouring values are more than Δs/100 apart,
  // and particles Δs apart would move in visible jumps or coincide.
  const double reach = std::max({std::abs(hf.xMax()), std::abs(hf.zMax()), std::abs(hf.minHeight()),
                                 std::abs(hf.maxHeight())});
  const double resolution = reach * 0x1.0p-23;
  if (resolution > 0.01 * ds) {
    const bool heights = std::max(std::abs(hf.minHeight()), std::abs(hf.maxHeight())) >=
                         std::max(hf.xMax(), hf.zMax());
    const char* field = !heights ? "terrain.length_x / length_z"
                        : std::abs(s.terrain.base) >= 0.5 * reach ? "terrain.base"
                                                                 : "terrain (its heights)";
    throw SceneError(format("%s: coordinates reach %g m from the origin, where float positions are %.3g m "
                            "apart: more than Δs/100 = %.3g m; keep the scene within %.3g m of the origin",
                            field, reach, resolution, 0.01 * ds, 0.01 * ds * 0x1.0p23));
  }
  const double x0 = hf.x0(), x1 = hf.xMax(), z0 = hf.z0(), z1 = hf.zMax();
  auto onTerrain = [&](double x, double z) { return x >= x0 && x <= x1 && z >= z0 && z <= z1; };
  const std::string rect = format("[%g, %g] × [%g, %g]", x0, x1, z0, z1);
  for (size_t k = 0; k < s.sources.size(); ++k) {
    const Eigen::Vector3d& c = s.sources[k].center;
    if (!onTerrain(c.x(), c.z()))
      throw SceneError(indexed("sources", k) + ".position: (x, z) = " + format("(%g, %g)", c.x(), c.z()) +
                       " is off the terrain " + rect);
    const double ground = hf.heightAt(c.x(), c.z());
    if (c.y() < ground)
      throw SceneError(indexed("sources", k) + ".position: " +
                       format("y = %g m is %.3g m below the terrain there (%g m)", c.y(), ground - c.y(), ground));
  }
  for (size_t k = 0; k < s.rain.size(); ++k)
    if (rainArea(s.rain[k], x0, x1, z0, z1) <= 0)
      throw SceneError(indexed("rain", k) + ": the rectangle " +
                       format("[%g, %g] × [%g, %g]", s.rain[k].lo_x, s.rain[k].hi_x, s.rain[k].lo_z, s.rain[k].hi_z) +
                       " does not overlap the terrain " + rect);
  for (size_t k = 0; k < s.sinks.size(); ++k)
    if (!((s.sinks[k].hi - s.sinks[k].lo).minCoeff() > 0))
      throw SceneError(indexed("sinks", k) + ": max must exceed min on every axis");
  const double slack = 1e-9 * std::max(x1 - x0, z1 - z0);
  for (size_t k = 0; k < s.blocks.size(); ++k) {
    const WaterBlock& b = s.blocks[k];
    const std::string at = indexed("water.blocks", k);
    if (b.min.x() < x0 - slack || b.max.x() > x1 + slack || b.min.z() < z0 - slack || b.max.z() > z1 + slack)
      throw SceneError(at + ": the box's (x, z) extent " +
                       format("[%g, %g] × [%g, %g]", b.min.x(), b.max.x(), b.min.z(), b.max.z()) +
                       " reaches beyond the terrain " + rect +
                       (s.domain.walls ? " and its closed walls" : ", whose open edges remove what leaves"));
    if (b.flood) {
      const Eigen::Vector2d& p = b.flood_from;
      if (!(p.x() >= b.min.x() && p.x() <= b.max.x() && p.y() >= b.min.z() && p.y() <= b.max.z()))
        throw SceneError(at + ".flood_from: " + format("(%g, %g)", p.x(), p.y()) +
                         " lies outside the block's (x, z) extent");
    }
  }
}

}  // namespace scour
