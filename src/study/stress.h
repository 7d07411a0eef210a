#pragma once
// `scour stress`: hard scenes that must stay numerically stable. Each scene is small enough to
// run in well under a minute; every step is checked against the invariants below, and the report
// keeps the worst value of each.
//
// The checks (a scene fails on the first one broken):
//   - no NaN or infinity in any particle's state;
//   - no particle deeper than 0.5 Δs below the terrain;
//   - no particle lost: the count equals the initial one plus those emitted (sources, rain,
//     brush) minus those removed by sinks and open walls, and none is beyond a closed wall;
//   - 0 ≤ C ≤ Cmax;
//   - the soil budget within 1e-6 relative;
//   - the kinetic energy bounded by what the sources and gravity can supply: the mechanical
//     energy Σ m(½|v|² + g y) never exceeds the ledger (the initial energy plus that brought by
//     every emitted particle, minus that taken out by every removed one) plus the elastic energy
//     stored in the initial pressure, by more than 5 % of the energy at hand (the ledger counted
//     from the lowest terrain point). The scheme is not exactly energy-conserving (the δ-SPH term
//     and the wall integrals are not derived from one potential): a 1.5 m column released at rest
//     gains about 1 % (docs/stress.md); a blow-up gains orders of magnitude.
// The engine's own checks (World::checkInvariants) cover the first five and stop a step that
// breaks them; the stress runner adds the count and energy checks and keeps the worst values.

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "scene/presets.h"

namespace scour {

/// A scene as `scour stress` runs it: for spec.stress.duration simulated seconds, with the
/// parameter jumps of spec.stress (scene/presets.h).
struct StressScene {
  std::string name, description;
  SceneSpec spec;
  long max_steps = 0;  ///< > 0: stop after this many steps, whichever comes first
};

/// The scenes, in report order.
const std::vector<std::string>& stressSceneNames();
/// The stress scene of assets/scenes/stress/<name>.json. Throws std::invalid_argument naming
/// the valid scenes for an unknown name.
StressScene stressScene(const std::string& name);
/// A scene run as its "stress" section says, under `name`.
StressScene stressSceneFrom(const SceneSpec& spec, const std::string& name);
/// The paper's canyon, lake and waterfall at full size, `steps` steps each, as stress scenes
/// (`scour stress --paper`; minutes each, not in CI).
std::vector<StressScene> paperStressScenes(long steps);

struct StressLimits {
  double penetration_over_ds = 0.5;
  double soil_relative = 1e-6;
  double energy_excess = 0.05;
};

struct StressResult {
  std::string name;
  long steps = 0;
  double simulated = 0, wall_seconds = 0, min_dt = 0, max_speed = 0;
  size_t particles_start = 0, particles_max = 0, particles_end = 0;
  long emitted = 0, removed = 0;
  // Worst values of the invariants.
  long nan = 0;
  double penetration_over_ds = 0;
  long lost = 0;
  double c_min = 0, c_max = 0, c_limit = 0;
  double soil_relative = 0;
  double energy_excess = 0;
  bool pass = true;
  std::string failure;  ///< the first broken check, with step and particle where known
};

/// Runs a scene to its duration (or its first failure). `progress` (may be empty) is called
/// every few hundred steps with the result so far. With a `trace` stream, one CSV line per step:
/// step, t, Δt, particles, kinetic and potential energy, ledger, max speed, penetration.
StressResult runStress(const StressScene& scene, const StressLimits& limits = {},
                       const std::function<void(const StressResult&)>& progress = {},
                       std::ostream* trace = nullptr);

/// The report as a Markdown table, one row per scene.
std::string stressTable(const std::vector<StressResult>& results, const StressLimits& limits);
/// The report as CSV, one row per scene, with a header.
std::string stressCsv(const std::vector<StressResult>& results);

}  // namespace scour
