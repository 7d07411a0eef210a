#include "scene/run_outputs.h"

#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <iomanip>

#include "engine/maps.h"
#include "engine/sediment.h"
#include "scene/checkpoint.h"
#include "scene/output.h"
#include "scene/scene_json.h"

namespace scour {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

std::string numbered(const char* pattern, long step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, pattern, step);
  return buf;
}

json passSecondsJson(const World& w) {
  json j = json::object();
  for (size_t p = 0; p < size_t(Pass::kCount); ++p)
    if (w.passCalls()[p] > 0) j[passName(Pass(p))] = w.passSeconds()[p];
  return j;
}

}  // namespace

std::string RunOutputs::frameName(long step) { return numbered("frame_%06ld.png", step); }

RunOutputs::RunOutputs(std::filesystem::path dir, RunOutputOptions o, const Scene& scene)
    : dir_(std::move(dir)), options_(o), scene_(scene) {
  // One row every K steps (and at step 0), cumulative pass seconds.
  metrics_ << "step,time_s,dt_s,particles,max_speed_m_s,terrain_m3,suspended_m3,removed_m3,"
              "soil_relative_error,morph_time_s,factor,bed_step_ds,morphological_m3,"
              "density_iterations,density_error,divergence_iterations,divergence_error";
  for (size_t p = 0; p < size_t(Pass::kCount); ++p) metrics_ << "," << passName(Pass(p)) << "_s";
  metrics_ << "\n";
}

void RunOutputs::metricsRow(const World& w, const StepStats& s) {
  const SoilBudget soil = w.soilBudget();
  metrics_ << w.steps() << "," << std::setprecision(9) << w.time() << "," << s.dt << ","
           << w.fluid().size() << "," << s.max_speed << "," << std::setprecision(15) << soil.terrain
           << "," << soil.suspended << "," << soil.removed << "," << soil.relativeError() << ","
           << std::setprecision(9) << w.morphologicalTime() << "," << s.factor << "," << s.bed_step_ds
           << "," << std::setprecision(15) << soil.morphological << std::setprecision(6) << ","
           << s.density_iterations << "," << s.density_error << "," << s.divergence_iterations << ","
           << s.divergence_error;
  for (size_t p = 0; p < size_t(Pass::kCount); ++p) metrics_ << "," << w.passSeconds()[p];
  metrics_ << "\n";
}

void RunOutputs::start(const World& w) {
  StepStats none;
  none.factor = w.factorNow();
  metricsRow(w, none);
  if (options_.particlesEvery > 0)
    writeParticlesPly(dir_ / numbered("particles_%06ld.ply", 0), w.fluid(),
                      w.params().particleVolume(), 0.0);
}

void RunOutputs::afterStep(const World& w, const StepRecord& r) {
  const long step = w.steps();
  SolverTally& t = solver_;
  t.smallestDt = t.steps == 0 ? r.stats.dt : std::min(t.smallestDt, r.stats.dt);
  ++t.steps, t.simulated += r.stats.dt;
  t.densityIterations += r.stats.density_iterations, t.divergenceIterations += r.stats.divergence_iterations;
  t.densityMost = std::max(t.densityMost, r.stats.density_iterations);
  t.divergenceMost = std::max(t.divergenceMost, r.stats.divergence_iterations);
  if (options_.particlesEvery > 0 && step % options_.particlesEvery == 0)
    writeParticlesPly(dir_ / numbered("particles_%06ld.ply", step), w.fluid(),
                      w.params().particleVolume(), w.time());
  if (step % options_.metricsEvery == 0) metricsRow(w, r.stats);
  if (options_.checkpointEvery > 0 && step % options_.checkpointEvery == 0)
    writeCheckpoint((dir_ / numbered("checkpoint_%06ld.ckpt", step)).string(), scene_.spec, w);
}

// Heights now and their change since the start, with how to read them back.
json writeErosionMaps(const fs::path& dir, const std::vector<TerrainMap>& maps, int nx, int nz,
                      const std::vector<std::string>& names, MapFormat format, const Georeference* where) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create directory '" + dir.string() + "': " + ec.message());
  const char* grid = "row k is z = z0 + k dz, column i is x = x0 + i dx";
  json out = json::object();
  for (const TerrainMap& m : maps) {
    if (std::find(names.begin(), names.end(), m.name) == names.end()) continue;
    const bool pair = !m.second.empty();
    json entry = {{"unit", m.unit}, {"meaning", m.meaning}};
    if (format == MapFormat::kExr) {
      if (pair)
        writeGridExr(dir / (m.name + ".exr"), nx, nz, {{"R", &m.values}, {"G", &m.second}});
      else
        writeGridExr(dir / (m.name + ".exr"), nx, nz, m.values);
      entry["file"] = m.name + ".exr";
      entry["mapping"] = std::string(pair ? "float32 channels R (x) and G (z)" : "float32 channel Y, the value in its unit") + "; " + grid;
    } else if (format == MapFormat::kGeoTiff) {
      std::vector<const std::vector<double>*> bands = {&m.values};
      if (pair) bands.push_back(&m.second);
      writeGeoTiff(dir / (m.name + ".tif"), nx, nz, bands, where ? *where : Georeference{}, m.unit,
                   {{"SCOUR_MAP", m.name}, {"SCOUR_MEANING", m.meaning}});
      entry["file"] = m.name + ".tif";
      entry["mapping"] = std::string(pair ? "float32 bands 1 (x) and 2 (z)" : "float32 band 1, the value in its unit") + "; " + grid;
    } else if (pair) {
      writeDirectionPng16(dir / (m.name + ".png"), nx, nz, m.values, m.second);
      entry["file"] = m.name + ".png";
      entry["mapping"] = std::string("16-bit RGB: x = 2 R / 65535 - 1, z = 2 G / 65535 - 1, B = 65535 where there is a direction; ") + grid;
    } else {
      entry["file"] = m.name + ".png";
      entry["white"] = writeMapPng16(dir / (m.name + ".png"), nx, nz, m.values);
      entry["mapping"] = std::string("value = v / 65535 * white; ") + grid;
    }
    out[m.name] = entry;
  }
  for (const std::string& n : names)
    if (!out.contains(n)) throw std::runtime_error("no erosion map called '" + n + "'");
  const std::string text = out.dump(2) + "\n";
  writeAtomically(dir / "maps.json", [&](std::ostream& o) { o << text; });
  return out;
}

std::vector<std::string> parseMapNames(const std::string& flag, const std::string& text) {
  const std::vector<std::string>& all = erosionMapNames();
  if (text == "all") return all;
  if (text == "none") return {};
  std::vector<std::string> names;
  size_t from = 0;
  while (from <= text.size()) {
    const size_t to = std::min(text.find(',', from), text.size());
    const std::string name = text.substr(from, to - from);
    if (!isErosionMap(name)) {
      std::string list;
      for (const std::string& a : all) list += (list.empty() ? "" : ", ") + a;
      throw std::invalid_argument(flag + ": no map called '" + name + "' (there is " + list + ", or all, or none)");
    }
    names.push_back(name);
    from = to + 1;
  }
  // Each once, in erosionMapNames()' order.
  std::vector<std::string> ordered;
  for (const std::string& a : all)
    if (std::find(names.begin(), names.end(), a) != names.end()) ordered.push_back(a);
  return ordered;
}

json RunOutputs::exports(const World& w) {
  const Heightfield hf = w.settledTerrain();
  auto [lo, hi] = writeHeightPng16(dir_ / "height.png", hf);
  writeHeightRaw(dir_ / "height.r32", hf);
  const double changeScale = writeErosionPng(dir_ / "erosion.png", hf, w.heightChange());
  if (options_.mesh) writeTerrainObj(dir_ / "mesh.obj", hf);
  json maps = options_.maps.empty() ? json(nullptr)
                                    : writeErosionMaps(dir_ / "maps", erosionMaps(w, options_.maps), hf.nx(), hf.nz(), options_.maps);
  return {{"maps", maps},
          {"height_png",
           {{"file", "height.png"},
            {"min_m", lo},
            {"max_m", hi},
            {"mapping",
             "h = min_m + v / 65535 * (max_m - min_m); row k is z = z0 + k dz, column i is x = "
             "x0 + i dx"}}},
          {"height_r32",
           {{"file", "height.r32"},
            {"nx", hf.nx()},
            {"nz", hf.nz()},
            {"dx", hf.dx()},
            {"dz", hf.dz()},
            {"format", "float32 little-endian, row-major: nz rows of nx heights [m]"}}},
          {"erosion_png",
           {{"file", "erosion.png"},
            {"scale_m", changeScale},
            {"mapping",
             "white: unchanged; red: erosion; blue: deposition; full colour at |dh| = scale_m"}}}};
}

namespace {

// The settled terrain's change since the start (measureTerrainChange).
json terrainChangeJson(const World& w) {
  const TerrainChange c = measureTerrainChange(w.heightChange(), w.vertexArea());
  return {{"max_erosion_m", c.max_erosion},
          {"max_deposition_m", c.max_deposition},
          {"eroded_m3", c.eroded},
          {"deposited_m3", c.deposited}};
}

}  // namespace

json RunOutputs::finish(const World& w, const RunEnd& end, double wallSeconds, const std::string& stoppedBy) {
  writeAtomically(dir_ / "metrics.csv", [&](std::ostream& out) { out << metrics_.str(); });
  json summary;
  summary["status"] = end.statusName();
  if (!end.message.empty()) summary["error"] = end.message;
  summary["stopped_by"] = end.ok() ? stoppedBy : std::string("error");
  summary["particles"] = w.fluid().size();
  summary["steps"] = w.steps();
  summary["sim_time_s"] = w.time();
  summary["wall_s"] = wallSeconds;
  summary["threads"] = omp_get_max_threads();
  summary["pass_seconds"] = passSecondsJson(w);
  // This run's steps (a resumed run's own, not the checkpoint's): what the step cost in wall
  // time per second of water, and what the implicit solver's iterations were.
  const SolverTally& t = solver_;
  const double perStep = t.steps > 0 ? 1.0 / double(t.steps) : 0.0;
  const ParamInfo& which = *findParam("fluid.solver");
  json solver = {{"name", which.choices[which.getChoice(w.params())]},
                 {"steps", t.steps},
                 {"mean_dt_s", t.simulated * perStep},
                 {"smallest_dt_s", t.smallestDt},
                 {"wall_s_per_simulated_s", t.simulated > 0 ? wallSeconds / t.simulated : 0.0}};
  if (w.params().solver == FluidSolver::kDfsph) {
    solver["density_iterations_per_step"] = double(t.densityIterations) * perStep;
    solver["divergence_iterations_per_step"] = double(t.divergenceIterations) * perStep;
    solver["most_density_iterations"] = t.densityMost;
    solver["most_divergence_iterations"] = t.divergenceMost;
  }
  summary["solver"] = solver;
  const InvariantReport& inv = w.invariants();
  summary["invariants"] = {{"nan", inv.nan},
                           {"max_penetration_over_ds", inv.max_penetration_over_ds},
                           {"escaped", inv.escaped},
                           {"terrain_contacts", w.terrainContacts()},
                           {"c_min", inv.c_min},
                           {"c_max", inv.c_max}};
  const SoilBudget soil = w.soilBudget();
  const SimParams& p = w.params();
  const Ledger::BedGuard& guard = w.bedGuard();
  summary["clock"] = {{"factor", w.morphologicalFactor()},
                      {"requested_factor", p.morphological_factor},
                      {"spinup_s", p.morphological_spinup},
                      {"hydraulic_s", w.time()},
                      {"morphological_s", w.morphologicalTime()}};
  summary["bed_guard"] = {{"bound_ds", p.max_bed_step},
                          {"lowered", guard.lowered},
                          {"lowest_factor", guard.lowered > 0 ? guard.lowest : w.morphologicalFactor()},
                          {"last_at_s", guard.lastAt}};
  summary["terrain_change"] = terrainChangeJson(w);
  summary["soil"] = {{"terrain_m3", soil.terrain},
                     {"suspended_m3", soil.suspended},
                     {"removed_m3", soil.removed},
                     {"initial_m3", soil.initial},
                     {"morphological_m3", soil.morphological},
                     {"relative_error", soil.relativeError()},
                     {"worst_relative_error", inv.soil_relative_error},
                     {"reference_height_m", w.initialTerrain().minHeight()}};
  summary["flow"] = {{"emitted", w.emitted()},
                     {"blocked_slots", w.blockedSlots()},
                     {"removed_by_sinks", w.removedBySinks()},
                     {"removed_by_outflow", w.removedByOutflow()}};
  std::ostringstream hash;
  hash << std::hex << std::setw(16) << std::setfill('0') << w.stateHash();
  summary["state_hash"] = hash.str();
  summary["scene"] = sceneToJson(scene_);
  summary["exports"] = exports(w);
  for (const auto& [key, value] : extra_.items()) summary[key] = value;
  writeAtomically(dir_ / "summary.json", [&](std::ostream& out) { out << summary.dump(2) << "\n"; });
  return summary;
}

}  // namespace scour
