#include <omp.h>
#include <unistd.h>

#include <algorithm>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "cli/commands.h"
#include "cli/render_options.h"
#include "engine/step_driver.h"
#include "scene/checkpoint.h"
#include "scene/output.h"
#include "scene/run_outputs.h"
#include "scene/scene_json.h"
#include "scene/timelapse.h"

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

std::unique_ptr<World> resumeFromCheckpoint(const std::string& path, Scene& scene, const std::string& prefix) {
  try {
    return std::make_unique<World>(resumeWorld(readCheckpoint(path), scene));
  } catch (const CheckpointError& e) {
    throw InputError(prefix + e.what());
  } catch (const SceneError& e) {
    throw InputError(prefix + path + ": " + e.what());
  } catch (const TerrainError& e) {
    throw InputError(prefix + path + ": terrain: " + e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(prefix + path + ": " + e.what());
  }
}

void createOutputDirectory(const std::string& flag, const std::string& path) {
  std::error_code ec;
  fs::create_directories(path, ec);
  if (ec || !fs::is_directory(path, ec))
    throw InputError(flag + ": cannot create directory '" + path + "'" + (ec ? ": " + ec.message() : ""));
}

namespace {

struct RunOptions {
  std::string scene;
  bool headless = false;
  long steps = 0;
  double time = 0;
  double wallTime = 0;  ///< > 0: stop once this many wall seconds have passed
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
  std::string maps = "none";  ///< erosion maps written at the end (parseMapNames)
  std::string timelapse;  ///< "K" steps or "Ss" seconds of bed time between pictures
  std::string timelapseVideo = "mp4";
  int timelapseFps = 24;
  RenderOptions render;
};

int runScene(const RunOptions& o) {
  setThreads(o.threads);
  Scene scene;
  std::unique_ptr<World> world;
  if (!o.resume.empty()) {
    // The scene, its overrides and the state all come from the checkpoint.
    world = resumeFromCheckpoint(o.resume, scene, "--resume: ");
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
  std::vector<std::string> maps;
  try {
    maps = parseMapNames("--maps", o.maps);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  std::unique_ptr<FrameWriter> frames;
  std::optional<Timelapse> timelapse;
  TimelapseOptions lapse;
  if (!o.timelapse.empty()) {
    try {
      parseTimelapseSpacing("--timelapse", o.timelapse, lapse);
      parseTimelapseVideo("--timelapse-video", o.timelapseVideo, lapse);
    } catch (const TimelapseError& e) {
      throw InputError(e.what());
    }
    lapse.fps = o.timelapseFps;
  }
  if (o.framesEvery > 0 || !o.timelapse.empty()) {
    frames = std::make_unique<FrameWriter>(o.render);
    if (scene.spec.has_camera)
      frames->setSceneCamera(scene.spec.camera_eye.cast<float>(), scene.spec.camera_target.cast<float>());
  }
  // The time-lapse first: without the program for its video, nothing is written.
  if (!o.timelapse.empty()) {
    try {
      timelapse.emplace(fs::path(o.out) / "timelapse", lapse);
    } catch (const TimelapseError& e) {
      throw InputError(e.what());
    }
  }
  createOutputDirectory("--out", o.out);
  const fs::path dir(o.out);
  // A time-lapse picture when one is due, numbered in order; its clocks in timelapse.csv.
  auto lapsePicture = [&](bool last) {
    if (!timelapse) return;
    if (last ? timelapse->lastStep() == world->steps() : !timelapse->due(world->steps(), world->morphologicalTime()))
      return;
    frames->write(makeFrame(*world, frames->map()), timelapse->nextPicture().string());
    timelapse->added(world->steps(), world->time(), world->morphologicalTime(), world->factorNow());
  };

  auto start = std::chrono::steady_clock::now();
  auto lastReport = start;
  const bool tty = ::isatty(2);
  // Progress from where this run starts (a resumed one: the checkpoint's step or time).
  const long firstStep = world->steps();
  const bool bySteps = o.steps > 0, byTime = o.time > 0;
  // Progress towards the first of the ends given; with --wall-time alone, towards it.
  RunProgress pace(bySteps ? double(firstStep) : byTime ? world->time() : 0.0,
                   bySteps ? double(o.steps) : byTime ? o.time : o.wallTime);
  auto wallSince = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  auto progress = [&](bool last) {
    double done = pace.fraction(), eta = pace.etaSeconds();
    if (o.wallTime > 0) {
      // Whichever end comes first.
      const double left = std::max(o.wallTime - wallSince(), 0.0);
      done = std::max(done, 1.0 - left / o.wallTime);
      eta = eta >= 0 ? std::min(eta, left) : left;
    }
    char line[240], etaText[32] = "ETA -", bed[64] = "";
    if (eta >= 0) std::snprintf(etaText, sizeof etaText, "ETA %.0f s", eta);
    // The bed's clock beside the water's once it runs apart (the geologic speed-up).
    if (world->morphologicalTime() != world->time())
      std::snprintf(bed, sizeof bed, " (bed %.4g s, N = %.4g)", world->morphologicalTime(), world->factorNow());
    std::snprintf(line, sizeof line, "step %ld  t = %.4g s%s  particles %zu  %3.0f%%  %s",
                  world->steps(), world->time(), bed, world->fluid().size(), 100 * done,
                  last ? "" : etaText);
    if (tty) {
      const int width = 30, filled = int(done * width + 0.5);
      std::cerr << "\r[" << std::string(size_t(std::clamp(filled, 0, width)), '#')
                << std::string(size_t(width - std::clamp(filled, 0, width)), ' ') << "] " << line
                << (last ? "\n" : "") << std::flush;
    } else if (!last) {
      std::cerr << line << "\n";
    }
  };
  RunOutputs outputs(dir, {o.particlesEvery, o.metricsEvery, o.checkpointEvery, o.mesh, maps}, scene);
  outputs.start(*world);
  if (o.framesEvery > 0) frames->write(makeFrame(*world, frames->map()), (dir / RunOutputs::frameName(world->steps())).string());
  lapsePicture(false);
  std::string stoppedBy = bySteps ? "steps" : "time";
  long guardSeen = world->bedGuard().lowered;
  auto more = [&] {
    if (bySteps && world->steps() >= o.steps) return stoppedBy = "steps", false;
    if (byTime && world->time() >= o.time - 1e-12) return stoppedBy = "time", false;
    if (o.wallTime > 0 && wallSince() >= o.wallTime) return stoppedBy = "wall_time", false;
    return true;
  };
  // Whatever a step (or an output after it) throws, the run still ends with its summary and the
  // documented code.
  const RunEnd end = runWhile(*world, more, [&](const StepRecord& record) {
    outputs.afterStep(*world, record);
    const Ledger::BedGuard& guard = world->bedGuard();
    if (guard.lowered != guardSeen) {
      guardSeen = guard.lowered;
      std::cerr << (tty ? "\r" : "") << "step " << world->steps() << " (t = " << world->time()
                << " s): the bed moved " << record.stats.bed_step_ds << " Δs in a step (bound "
                << world->params().max_bed_step << "): geologic speed-up lowered from "
                << guard.lastFrom << " to " << world->morphologicalFactor() << "\n";
    }
    if (o.framesEvery > 0 && world->steps() % o.framesEvery == 0)
      frames->write(makeFrame(*world, frames->map()), (dir / RunOutputs::frameName(world->steps())).string());
    lapsePicture(false);
    auto now = std::chrono::steady_clock::now();
    const double wall = std::chrono::duration<double>(now - start).count();
    // With --wall-time alone the run's progress is the wall time itself.
    pace.add(wall, bySteps ? double(world->steps()) : byTime ? world->time() : wall);
    // A terminal gets a live bar; a log gets one plain line every few seconds.
    if (now - lastReport > (tty ? std::chrono::milliseconds(200) : std::chrono::milliseconds(5000))) {
      lastReport = now;
      progress(false);
    }
  });
  if (tty) progress(true);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::string videoProblem;
  if (timelapse) {
    if (end.ok()) lapsePicture(true);  // the time-lapse ends on the state the run ends on
    try {
      videoProblem = timelapse->finish();
    } catch (const std::exception& e) {  // the run's own outputs and summary still come
      videoProblem = e.what();
    }
    json entry = {{"pictures", timelapse->pictures()},
                  {"folder", fs::relative(timelapse->folder(), dir).string()},
                  {"every_steps", lapse.everySteps},
                  {"every_bed_s", lapse.everyBedSeconds},
                  {"fps", lapse.fps}};
    if (!timelapse->videoPath().empty())
      entry["video"] = videoProblem.empty() ? json(fs::relative(timelapse->videoPath(), dir).string()) : json(nullptr);
    if (!videoProblem.empty()) entry["video_problem"] = videoProblem;
    outputs.addToSummary("timelapse", entry);
  }
  outputs.finish(*world, end, wall, stoppedBy);
  if (!end.ok()) {
    std::cerr << "error: " << end.describe() << "\n"
              << "summary written to " << (dir / "summary.json").string() << "\n";
    return exitCode(end);
  }
  std::cout << "ran " << world->steps() - firstStep << " steps";
  if (firstStep > 0) std::cout << " (from step " << firstStep << " to " << world->steps() << ")";
  std::cout << " (" << world->time() << " s simulated";
  if (world->morphologicalTime() != world->time()) std::cout << ", " << world->morphologicalTime() << " s of bed time";
  std::cout << ", " << world->fluid().size() << " particles) in " << wall << " s";
  if (stoppedBy == "wall_time") std::cout << " (the wall-time budget)";
  std::cout << "; outputs in " << dir.string() << "\n";
  if (timelapse) {
    std::cout << "time-lapse: " << timelapse->pictures() << " pictures in " << timelapse->folder().string();
    if (!timelapse->videoPath().empty() && videoProblem.empty())
      std::cout << ", the video " << timelapse->videoPath().string();
    std::cout << "\n";
    // The pictures are there, but a video asked for was not made: the run did not do all it was told.
    if (!videoProblem.empty() && videoProblem != "one picture makes no video") {
      std::cerr << "error: time-lapse video: " << videoProblem << "\n";
      return kExitFailure;
    }
    if (!videoProblem.empty()) std::cerr << "note: time-lapse: " << videoProblem << "\n";
  }
  return kExitOk;
}

}  // namespace

Command addRunCommand(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* c = app.add_subcommand("run", "Run a scene and write its outputs");
  auto* scene = c->add_option("scene", o->scene,
                              "Built-in scene name (see `scour presets`) or a scene file (.json)");
  c->add_flag("--headless", o->headless, "Ignored: run never opens a window (kept for old scripts)");
  auto* steps = c->add_option("--steps", o->steps, "Number of steps")->check(kPositive);
  auto* time = c->add_option("--time", o->time, "Simulated seconds")->check(kPositive);
  steps->excludes(time);
  auto* wallTime = c->add_option("--wall-time", o->wallTime,
                                 "End cleanly after this many wall seconds (alone, or with --steps/--time: whichever comes first)")
                       ->check(kPositive);
  c->add_option("--out", o->out, "Output directory")->required();
  c->add_option("--threads", o->threads, "OpenMP threads (default: all cores)")->check(kPositive);
  c->add_option("--particles-every", o->particlesEvery, "Write particles_<step>.ply every K steps")
      ->check(kPositive);
  c->add_option("--scale", o->scale, "Scale the preset's particle count")->check(kPositive);
  c->add_option("--metrics-every", o->metricsEvery, "Write a metrics.csv row every K steps (default 10)")
      ->check(kPositive);
  c->add_flag("--mesh", o->mesh, "Also write the final terrain as mesh.obj (with normals)");
  c->add_option("--maps", o->maps, "Erosion maps written at the end into maps/: none (default), all, or a list of wear, deposition, sediment, flow, wetness, shear_peak, shear_mean, flow_direction");
  auto* sets = c->add_option("--set", o->sets, "Override a parameter: key=value (repeatable)");
  c->add_option("--checkpoint-every", o->checkpointEvery,
                "Write checkpoint_<step>.ckpt every K steps (resume with --resume)")
      ->check(kPositive);
  c->add_option("--frames", o->framesEvery, "Render frame_<step>.png every K steps (and at the start)")
      ->check(kPositive);
  c->add_option("--timelapse", o->timelapse,
                "A time-lapse: a picture every K steps (250) or every S seconds of bed time (0.5s) in "
                "timelapse/, and a video of them (needs the ffmpeg program)");
  c->add_option("--timelapse-video", o->timelapseVideo, "The time-lapse's video: mp4 (default), gif or none");
  c->add_option("--timelapse-fps", o->timelapseFps, "The time-lapse video's frames per second (default 24)")
      ->check(CLI::Range(1, 240));
  addRenderOptions(c, o->render);
  auto* resume = c->add_option("--resume", o->resume,
                               "Continue from a checkpoint (--steps/--time: the total to reach)");
  resume->excludes(scene);
  resume->excludes(sets);
  return [o, steps, time, wallTime, scene, resume] {
    if (scene->count() == 0 && resume->count() == 0)
      throw InputError("run: a scene (name or file) or --resume FILE is required");
    if (steps->count() == 0 && time->count() == 0 && wallTime->count() == 0)
      throw InputError("run: one of --steps, --time or --wall-time is required");
    if (resume->count() > 0 && o->scale != 1.0)
      throw InputError("--scale: a resumed run keeps the checkpoint's scene; drop --scale");
    return runScene(*o);
  };
}

}  // namespace scour
