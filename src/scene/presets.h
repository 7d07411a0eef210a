#pragma once
// Built-in scenes. Each preset is defined once here and shared by `scour run`, `scour bench` and
// the tests. `scale` multiplies the particle count (roughly), for quick runs.

#include <string>
#include <vector>

#include "engine/world.h"

namespace scour {

struct Scene {
  std::string name;
  std::string description;
  WorldDesc desc;
  /// Free-form description of how the terrain was made (goes into the resolved scene JSON).
  std::string terrain_kind;
  /// Axis-aligned blocks the initial water was made of, as (lo, hi) pairs [m].
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> water_blocks;
};

struct PresetInfo {
  const char* name;
  const char* description;
};
const std::vector<PresetInfo>& presetList();

/// Builds a preset. `particles` > 0 asks for about that many particles where the preset supports
/// it (the bench block). Throws std::invalid_argument for an unknown name, naming the valid ones.
Scene makePreset(const std::string& name, double scale = 1.0, long particles = 0);

/// Fills the box [lo, hi] with particles on a cubic lattice of spacing Δs, centred in each cell.
void fillBlock(Scene& s, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

}  // namespace scour
