#include <omp.h>
#include <unistd.h>

#include <algorithm>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "cli/commands.h"
#include "cli/render_options.h"
#include "scene/checkpoint.h"
#include "scene/output.h"
#include "scene/scene_json.h"

namespace scour {

namespace fs = std::filesystem;
using nlohmann::json;

const CLI::Validator kPositive(
    [](std::string& s) -> std::string {
      char* end = nullptr;
      double v = std::strtod(s.c_str(), &end);
      if (s.empty() || end != s.c_str() + s.size()) return "expected a number, found '" + s + "'";
      if (!std::isfinite(v) || v <= 0) return "must be a finite number > 0, found '" + s + "'";
      return {};
    },
    "POSITIVE");

void setThreads(int threads) {
  if (threads > 0) omp_set_num_threads(threads);
}

void applySets(SimParams& params, const std::vector<std::string>& sets) {
  for (const std::string& kv : sets) {
    auto eq = kv.find('=');
    if (eq == std::string::npos)
      throw InputError("--set: expected key=value, found '" + kv + "'");
    std::string err = setParam(params, kv.substr(0, eq), kv.substr(eq + 1));
    if (!err.empty()) throw InputError("--set: " + err);
  }
}

Scene loadScene(const std::string& name, double scale, long particles,
                const std::vector<std::string>& sets) {
  SceneSpec spec;
  const bool file = name.find('/') != std::string::npos || name.ends_with(".json");
  try {
    if (file) {
      spec = loadSceneFile(name);
      applyScaling(spec, scale, particles);
    } else {
      spec = presetSpec(name, scale, particles);
    }
  } catch (const SceneError& e) {
    throw InputError(e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  // Overrides edit the spec before it is built, so a new Δs refills the water at that spacing.
  applySets(spec.params, sets);
  try {
    return buildScene(spec);
  } catch (const TerrainError& e) {
    throw InputError(std::string("terrain: ") + e.what());
  } catch (const SceneError& e) {
    throw InputError(name + ": " + e.what());
  }
}

namespace {

struct RunOptions {
  std::string scene;
  bool headless = false;
  long steps = 0;
  double time = 0;
  std::string out;
  int threads = 0;
  long particlesEvery = 0;
  long metricsEvery = 10;
  bool mesh = false;
  double scale = 1.0;
  std::vector<std::string> sets;
  long checkpointEvery = 0;
  std::string resume;
  long framesEvery = 0;
  RenderOptions render;
};

std::string frameName(long step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "frame_%06ld.png", step);
  return buf;
}

std::string checkpointName(long step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "checkpoint_%06ld.ckpt", step);
  return buf;
}

std::string plyName(long step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "particles_%06ld.ply", step);
  return buf;
}

json passSecondsJson(const World& w) {
  json j = json::object();
  for (size_t p = 0; p < size_t(Pass::kCount); ++p)
    if (w.passCalls()[p] > 0) j[passName(Pass(p))] = w.passSeconds()[p];
  return j;
}

int runScene(const RunOptions& o) {
  setThreads(o.threads);
  Scene scene;
  std::unique_ptr<World> world;
  if (!o.resume.empty()) {
    // The scene, its overrides and the state all come from the checkpoint.
    try {
      const Checkpoint c = readCheckpoint(o.resume);
      world = std::make_unique<World>(resumeWorld(c, scene));
    } catch (const CheckpointError& e) {
      throw InputError(std::string("--resume: ") + e.what());
    } catch (const SceneError& e) {
      throw InputError("--resume: " + o.resume + ": " + e.what());
    } catch (const TerrainError& e) {
      throw InputError("--resume: " + o.resume + ": terrain: " + e.what());
    } catch (const std::invalid_argument& e) {
      throw InputError("--resume: " + o.resume + ": " + e.what());
    }
    if (o.steps > 0 && o.steps <= world->steps())
      throw InputError("--steps: the checkpoint is at step " + std::to_string(world->steps()) +
                       "; --steps is the total to reach, so it must be larger");
    if (o.time > 0 && o.time <= world->time())
      throw InputError("--time: the checkpoint is at t = " + std::to_string(world->time()) +
                       " s; --time is the total to reach, so it must be larger");
  } else {
    scene = loadScene(o.scene, o.scale, 0, o.sets);
    try {
      world = std::make_unique<World>(scene.desc);
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("scene '") + o.scene + "': " + e.what());
    }
  }
  // Pictures: the GL context and renderer are made (and their options checked) before any output.
  std::unique_ptr<FrameWriter> frames;
  if (o.framesEvery > 0) {
    frames = std::make_unique<FrameWriter>(o.render);
    if (scene.spec.has_camera)
      frames->setSceneCamera(scene.spec.camera_eye.cast<float>(), scene.spec.camera_target.cast<float>());
  }
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec || !fs::is_directory(o.out))
    throw InputError("--out: cannot create directory '" + o.out + "'" +
                     (ec ? ": " + ec.message() : ""));
  const fs::path dir(o.out);

  auto start = std::chrono::steady_clock::now();
  auto lastReport = start;
  const bool tty = ::isatty(2);
  // metrics.csv: one row every K steps (and at step 0), cumulative pass seconds; written whole
  // at the end, through a temporary file.
  std::ostringstream metrics;
  metrics << "step,time_s,dt_s,particles,max_speed_m_s,terrain_m3,suspended_m3,removed_m3,"
             "soil_relative_error";
  for (size_t p = 0; p < size_t(Pass::kCount); ++p) metrics << "," << passName(Pass(p)) << "_s";
  metrics << "\n";
  auto metricsRow = [&](double dt, double maxSpeed) {
    const SoilBudget soil = world->soilBudget();
    metrics << world->steps() << "," << std::setprecision(9) << world->time() << "," << dt << ","
            << world->fluid().size() << "," << maxSpeed << "," << std::setprecision(15)
            << soil.terrain << "," << soil.suspended << "," << soil.removed << ","
            << soil.relativeError() << std::setprecision(6);
    for (size_t p = 0; p < size_t(Pass::kCount); ++p) metrics << "," << world->passSeconds()[p];
    metrics << "\n";
  };
  metricsRow(0.0, 0.0);
  auto progress = [&](bool last) {
    const double done = o.steps > 0 ? double(world->steps()) / double(o.steps) : world->time() / o.time;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double eta = done > 0 ? elapsed * (1 - done) / done : 0;
    char line[200];
    std::snprintf(line, sizeof line, "step %ld  t = %.4g s  particles %zu  %3.0f%%  ETA %.0f s",
                  world->steps(), world->time(), world->fluid().size(), 100 * done, eta);
    if (tty) {
      const int width = 30, filled = int(done * width + 0.5);
      std::cerr << "\r[" << std::string(size_t(std::clamp(filled, 0, width)), '#')
                << std::string(size_t(width - std::clamp(filled, 0, width)), ' ') << "] " << line
                << (last ? "\n" : "") << std::flush;
    } else if (!last) {
      std::cerr << line << "\n";
    }
  };
  if (o.particlesEvery > 0) writeParticlesPly(dir / plyName(0), world->fluid(), world->params().particleVolume(), 0.0);
  if (frames) frames->write(makeFrame(*world), (dir / frameName(world->steps())).string());
  std::string failure, status = "ok";
  try {
    while (o.steps > 0 ? world->steps() < o.steps : world->time() < o.time - 1e-12) {
      const StepStats st = world->step();
      if (o.particlesEvery > 0 && world->steps() % o.particlesEvery == 0)
        writeParticlesPly(dir / plyName(world->steps()), world->fluid(),
                          world->params().particleVolume(), world->time());
      if (world->steps() % o.metricsEvery == 0) metricsRow(st.dt, st.max_speed);
      if (frames && world->steps() % o.framesEvery == 0)
        frames->write(makeFrame(*world), (dir / frameName(world->steps())).string());
      if (o.checkpointEvery > 0 && world->steps() % o.checkpointEvery == 0)
        writeCheckpoint((dir / checkpointName(world->steps())).string(), scene.spec, *world);
      auto now = std::chrono::steady_clock::now();
      // A terminal gets a live bar; a log gets one plain line every few seconds.
      if (now - lastReport > (tty ? std::chrono::milliseconds(200) : std::chrono::milliseconds(5000))) {
        lastReport = now;
        progress(false);
      }
    }
  } catch (const InvariantViolation& e) {
    failure = e.what(), status = "invariant_violated";
  } catch (const LimitExceeded& e) {
    failure = e.what(), status = "limit_exceeded";
  } catch (const std::exception& e) {
    // Whatever else a step throws (memory, an output that cannot be written), the run still
    // ends with its summary and the documented code.
    failure = e.what(), status = "failed";
  }
  if (tty) progress(true);
  writeAtomically(dir / "metrics.csv", [&](std::ostream& out) { out << metrics.str(); });
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  json summary;
  summary["status"] = status;
  if (!failure.empty()) summary["error"] = failure;
  summary["particles"] = world->fluid().size();
  summary["steps"] = world->steps();
  summary["sim_time_s"] = world->time();
  summary["wall_s"] = wall;
  summary["threads"] = omp_get_max_threads();
  summary["pass_seconds"] = passSecondsJson(*world);
  const InvariantReport& inv = world->invariants();
  summary["invariants"] = {{"nan", inv.nan},
                           {"max_penetration_over_ds", inv.max_penetration_over_ds},
                           {"escaped", inv.escaped},
                           {"c_min", inv.c_min},
                           {"c_max", inv.c_max}};
  const SoilBudget soil = world->soilBudget();
  summary["soil"] = {{"terrain_m3", soil.terrain},
                     {"suspended_m3", soil.suspended},
                     {"removed_m3", soil.removed},
                     {"initial_m3", soil.initial},
                     {"relative_error", soil.relativeError()},
                     {"worst_relative_error", inv.soil_relative_error},
                     {"reference_height_m", world->initialTerrain().minHeight()}};
  summary["flow"] = {{"emitted", world->emitted()},
                     {"blocked_slots", world->blockedSlots()},
                     {"removed_by_sinks", world->removedBySinks()},
                     {"removed_by_outflow", world->removedByOutflow()}};
  std::ostringstream hash;
  hash << std::hex << std::setw(16) << std::setfill('0') << world->stateHash();
  summary["state_hash"] = hash.str();
  summary["scene"] = sceneToJson(scene);
  // Terrain exports: heights now, and the change since the start.
  auto [lo, hi] = writeHeightPng16(dir / "height.png", world->terrain());
  writeHeightRaw(dir / "height.r32", world->terrain());
  const double changeScale = writeErosionPng(dir / "erosion.png", world->terrain(), world->heightChange());
  if (o.mesh) writeTerrainObj(dir / "mesh.obj", world->terrain());
  const Heightfield& hf = world->terrain();
  summary["exports"] = {
      {"height_png",
       {{"file", "height.png"}, {"min_m", lo}, {"max_m", hi},
        {"mapping", "h = min_m + v / 65535 * (max_m - min_m); row k is z = z0 + k dz, column i is x = x0 + i dx"}}},
      {"height_r32",
       {{"file", "height.r32"}, {"nx", hf.nx()}, {"nz", hf.nz()}, {"dx", hf.dx()}, {"dz", hf.dz()},
        {"format", "float32 little-endian, row-major: nz rows of nx heights [m]"}}},
      {"erosion_png",
       {{"file", "erosion.png"}, {"scale_m", changeScale},
        {"mapping", "white: unchanged; red: erosion; blue: deposition; full colour at |dh| = scale_m"}}}};
  writeAtomically(dir / "summary.json", [&](std::ostream& out) { out << summary.dump(2) << "\n"; });

  if (!failure.empty()) {
    const char* what = status == "invariant_violated" ? "invariant violated at "
                       : status == "limit_exceeded"   ? "limit reached at "
                                                      : "the run failed: ";
    std::cerr << "error: " << what << failure << "\n"
              << "summary written to " << (dir / "summary.json").string() << "\n";
    return status == "failed" ? kExitFailure : kExitInvariant;
  }
  std::cout << "ran " << world->steps() << " steps (" << world->time() << " s simulated, "
            << world->fluid().size() << " particles) in " << wall << " s; outputs in "
            << dir.string() << "\n";
  return kExitOk;
}

}  // namespace

Command addRunCommand(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* c = app.add_subcommand("run", "Run a scene and write its outputs");
  auto* scene = c->add_option("scene", o->scene,
                              "Built-in scene name (see `scour presets`) or a scene file (.json)");
  c->add_flag("--headless", o->headless, "Run without a window");
  auto* steps = c->add_option("--steps", o->steps, "Number of steps")->check(kPositive);
  auto* time = c->add_option("--time", o->time, "Simulated seconds")->check(kPositive);
  steps->excludes(time);
  c->add_option("--out", o->out, "Output directory")->required();
  c->add_option("--threads", o->threads, "OpenMP threads (default: all cores)")->check(kPositive);
  c->add_option("--particles-every", o->particlesEvery, "Write particles_<step>.ply every K steps")
      ->check(kPositive);
  c->add_option("--scale", o->scale, "Scale the preset's particle count")->check(kPositive);
  c->add_option("--metrics-every", o->metricsEvery, "Write a metrics.csv row every K steps (default 10)")
      ->check(kPositive);
  c->add_flag("--mesh", o->mesh, "Also write the final terrain as mesh.obj (with normals)");
  auto* sets = c->add_option("--set", o->sets, "Override a parameter: key=value (repeatable)");
  c->add_option("--checkpoint-every", o->checkpointEvery,
                "Write checkpoint_<step>.ckpt every K steps (resume with --resume)")
      ->check(kPositive);
  c->add_option("--frames", o->framesEvery, "Render frame_<step>.png every K steps (and at the start)")
      ->check(kPositive);
  addRenderOptions(c, o->render);
  auto* resume = c->add_option("--resume", o->resume,
                               "Continue from a checkpoint (--steps/--time: the total to reach)");
  resume->excludes(scene);
  resume->excludes(sets);
  return [o, steps, time, scene, resume] {
    if (scene->count() == 0 && resume->count() == 0)
      throw InputError("run: a scene (name or file) or --resume FILE is required");
    if (steps->count() == 0 && time->count() == 0)
      throw InputError("run: one of --steps or --time is required");
    if (resume->count() > 0 && o->scale != 1.0)
      throw InputError("--scale: a resumed run keeps the checkpoint's scene; drop --scale");
    return runScene(*o);
  };
}

}  // namespace scour
