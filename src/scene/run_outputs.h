#pragma once
// What `scour run` writes into its output directory, except the pictures (they need GL and are
// the command's): particles every N steps, checkpoints every N steps, metrics.csv (a row every N
// steps), and at the end the terrain exports and summary.json (docs/cli.md). Every file goes
// through writeAtomically, so a run that stops leaves no half-written file.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "engine/maps.h"
#include "engine/step_driver.h"
#include "scene/geodata.h"
#include "scene/presets.h"

namespace scour {

/// The maps named (of `maps`, on an nx × nz grid) as DIR/<name>.png (writeMapPng16; `exr`:
/// DIR/<name>.exr, float32, the values in their unit), and DIR/maps.json saying for each its
/// file, unit, meaning and (PNG) the value white stands for; DIR is made. Returns maps.json's
/// object. std::runtime_error for a name not among the maps.
enum class MapFormat { kPng16, kExr, kGeoTiff };
/// `format` kExr: float32 EXR, two-channel maps as R and G; kGeoTiff: float32 GeoTIFF (two bands
/// for a two-channel map) with the georeference `where` (none when null); kPng16: flow_direction
/// as writeDirectionPng16.
nlohmann::json writeErosionMaps(const std::filesystem::path& dir, const std::vector<TerrainMap>& maps, int nx,
                                int nz, const std::vector<std::string>& names, MapFormat format = MapFormat::kPng16,
                                const Georeference* where = nullptr);
/// "all", "none" or a comma-separated list of erosionMapNames(), each once in that order;
/// std::invalid_argument naming `flag` otherwise.
std::vector<std::string> parseMapNames(const std::string& flag, const std::string& text);

struct RunOutputOptions {
  long particlesEvery = 0;   ///< > 0: particles_<step>.ply every this many steps (and at 0)
  long metricsEvery = 10;    ///< a metrics.csv row every this many steps (and at 0)
  long checkpointEvery = 0;  ///< > 0: checkpoint_<step>.ckpt every this many steps
  bool mesh = false;         ///< also mesh.obj at the end
  std::vector<std::string> maps;  ///< erosion maps to write at the end into maps/
};

class RunOutputs {
 public:
  /// `dir` exists; `scene` is what the summary and the checkpoints record.
  RunOutputs(std::filesystem::path dir, RunOutputOptions o, const Scene& scene);

  /// Before the first step: the first particles file and metrics row.
  void start(const World& w);
  /// After each step.
  void afterStep(const World& w, const StepRecord& r);
  /// At the end, however the run ended: metrics.csv, the terrain exports and summary.json
  /// (its "status" is end.statusName(), its "error" the message, its "stopped_by" `stoppedBy`
  /// for a run that ended well: "steps", "time" or "wall_time"). Returns the summary.
  nlohmann::json finish(const World& w, const RunEnd& end, double wallSeconds, const std::string& stoppedBy);

  /// An entry the summary gets besides its own (the run's time-lapse, say).
  void addToSummary(const std::string& key, nlohmann::json value) { extra_[key] = std::move(value); }

  /// "frame_000120.png": the name of a picture of step `step`.
  static std::string frameName(long step);

 private:
  void metricsRow(const World& w, const StepStats& s);
  nlohmann::json exports(const World& w);

  std::filesystem::path dir_;
  RunOutputOptions options_;
  const Scene& scene_;
  std::ostringstream metrics_;
  /// The run's steps as the solver saw them (summary.json "solver"): this run's steps, the water
  /// time they covered, the solves' iterations summed and at most.
  struct SolverTally {
    long steps = 0;
    double simulated = 0, smallestDt = 0;
    long densityIterations = 0, divergenceIterations = 0;
    int densityMost = 0, divergenceMost = 0;
  } solver_;
  nlohmann::json extra_ = nlohmann::json::object();
};

}  // namespace scour
