#include <omp.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <thread>
#include <tuple>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "app/app.h"
#include "app/worker.h"
#include "cli/commands.h"
#include "cli/render_options.h"
#include "engine/step_driver.h"
#include "render/context.h"
#include "render/renderer.h"
#include "scene/scene_json.h"

namespace scour {

using nlohmann::json;

namespace {

// A run of steps that did not end well: the message, and the exit code run would give.
int stepFailure(const RunEnd& end, const std::string& scene = "") {
  std::cerr << "error: " << (scene.empty() ? "" : scene + ": ") << end.describe() << "\n";
  return exitCode(end);
}

struct BenchOptions {
  std::string scene = "block";
  long particles = 0;
  long steps = 20;
  long warmup = 3;
  int threads = 0;
  double scale = 1.0;
  bool json = false;
  bool erosion = false;
  bool ablation = false;
  bool render = false;
  bool paper = false;
  bool withWindow = false;
  bool presets = false;
  std::vector<double> scales{0.1, 0.3, 1.0};
  int repeat = 1;
  double seconds = 5;
  std::string size;  ///< empty: 960x540 for --render, the window's 1280x720 for --with-window
  std::vector<std::string> sets;
  std::vector<std::string> sideBySide;  ///< settings to compare, each "key=value ..." on top of sets
};

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// K: the scene's bed works every K steps (erosion.exchange_every, at least 1).
long exchangeEvery(const World& w) { return w.params().exchange_every; }

// Steps to time: `steps` rounded up to whole windows of K steps, each holding the bed's work once.
long timedSteps(long steps, const World& w) {
  const long k = exchangeEvery(w);
  return (steps + k - 1) / k * k;
}

// Each step's seconds as the means of consecutive windows of k steps (k = 1: the steps), so that
// a median over them counts the bed's work of a scene that does it every k-th step at its cost
// per step, not at the k − 1 steps without it. A last window shorter than k is left out unless it
// is the only one.
std::vector<double> windowMeans(const std::vector<double>& v, long k) {
  if (k <= 1) return v;
  std::vector<double> means;
  for (size_t at = 0; at < v.size(); at += size_t(k)) {
    const size_t end = std::min(v.size(), at + size_t(k));
    if (end - at < size_t(k) && !means.empty()) break;
    double sum = 0;
    for (size_t i = at; i < end; ++i) sum += v[i];
    means.push_back(sum / double(end - at));
  }
  return means;
}

// Effects off cost nothing: the scene with every effect, with the erosion effects off, and with
// SPH alone (fluid motion and the scene's friction; no erosion, sources, sinks or rain), stepped
// in turn so that the machine's drift hits all three alike.
int ablation(const BenchOptions& o, const Scene& scene) {
  struct Config {
    const char* name;
    Effects fx;
  };
  Effects all = scene.desc.effects, noErosion = all, sph;
  all.erosion = all.settling = all.diffusion = all.deposition = true;
  noErosion.erosion = noErosion.settling = noErosion.diffusion = noErosion.deposition = false;
  sph = noErosion;
  sph.sources = sph.sinks = sph.rain = false;
  std::vector<Config> configs = {{"all effects", all}, {"erosion off", noErosion}, {"SPH only", sph}};
  std::vector<std::unique_ptr<World>> worlds;
  for (const Config& c : configs) {
    WorldDesc d = scene.desc;
    d.effects = c.fx;
    if (c.fx.erosion) d.concentration.assign(d.particles.size(), 0.01);
    worlds.push_back(std::make_unique<World>(d));
  }
  // Warm up first: the warm-up steps, and at least a second of them all (a cold machine's first
  // pass read 2.5 where reruns read 1.09: first-touch pages, the thread pool, the clock ramping).
  const auto warmStart = std::chrono::steady_clock::now();
  long warmed = 0;
  for (; warmed < 200; ++warmed) {
    const double warm =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - warmStart).count();
    if (warmed >= o.warmup && warm >= 1.0) break;
    for (auto& w : worlds)
      if (const RunEnd end = runSteps(*w, 1); !end.ok()) return stepFailure(end);
  }
  std::vector<std::vector<double>> t(configs.size());
  const long steps = timedSteps(o.steps, *worlds[0]);
  for (long s = 0; s < steps; ++s)
    for (size_t c = 0; c < configs.size(); ++c) {
      const RunEnd end =
          runSteps(*worlds[c], 1, [&](const StepRecord& r) { t[c].push_back(r.seconds); });
      if (!end.ok()) return stepFailure(end);
    }
  json j;
  j["scene"] = o.scene;
  j["particles"] = worlds[0]->fluid().size();
  j["threads"] = omp_get_max_threads();
  j["steps"] = steps;
  j["warmup_steps"] = warmed;
  for (size_t c = 0; c < configs.size(); ++c) t[c] = windowMeans(t[c], exchangeEvery(*worlds[0]));
  for (size_t c = 0; c < configs.size(); ++c) j["seconds_per_step"][configs[c].name] = median(t[c]);
  const double ratio = median(t[1]) / median(t[2]);
  j["erosion_off_over_sph_only"] = ratio;
  if (o.json) {
    std::cout << j.dump(2) << "\n";
    return kExitOk;
  }
  std::printf(
      "scene %s: %zu particles, %d threads, %ld steps each after %ld warm-up steps (median "
      "seconds per step)\n",
      o.scene.c_str(), worlds[0]->fluid().size(), omp_get_max_threads(), steps, warmed);
  for (size_t c = 0; c < configs.size(); ++c)
    std::printf("  %-12s %10.6f\n", configs[c].name, median(t[c]));
  std::printf("erosion off / SPH only = %.3f (1 = an effect that is off costs nothing)\n", ratio);
  return kExitOk;
}

// The renderer's passes at a scene's size: GPU time (timer queries; CPU time on llvmpipe) of
// splatting, listing the occupied blocks and marching tetrahedra, and the wall time of shading,
// with the occupancy grid and without it.
int benchRender(const BenchOptions& o, const Scene& scene) {
  World world(scene.desc);
  if (const RunEnd end = runSteps(world, o.warmup); !end.ok()) return stepFailure(end);
  const Frame frame = makeFrame(world);
  const auto [w, h] = parseSize(o.size.empty() ? "960x540" : o.size, 16);
  const auto context = createGlContext(GlBackend::kEgl);
  Renderer r(w, h);
  const Camera cam = overviewCamera(frame);
  struct Result {
    std::vector<double> splat, occupancy, march, surface, shading, frame, find;
    SurfaceStats stats;
    long isoCubes = 0;
  } res[2];
  for (int pass = 0; pass < 2; ++pass) {
    RenderSettings s;
    s.surface.occupancy = pass == 0;
    s.surface.profile = true;
    r.render(frame, cam, s);
    while (r.surface().growIfOverflowed()) r.render(frame, cam, s);
    for (long k = 0; k < o.steps; ++k) {
      glFinish();
      auto t0 = std::chrono::steady_clock::now();
      r.render(frame, cam, s);
      glFinish();
      const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const WaterSurface::Timings t = r.surface().readTimings();
      const double surface = t.splat + t.occupancy + t.march;
      res[pass].splat.push_back(t.splat), res[pass].occupancy.push_back(t.occupancy);
      res[pass].march.push_back(t.march), res[pass].surface.push_back(surface);
      res[pass].shading.push_back(std::max(total - surface, 0.0)), res[pass].frame.push_back(total);
      double find = 0;
      res[pass].isoCubes = r.surface().countIsoCubes(&find);
      res[pass].find.push_back(find + t.occupancy);  // listing the blocks is part of finding
    }
    res[pass].stats = r.surface().readStats();
  }
  json j;
  j["scene"] = o.scene;
  j["particles"] = frame.particles();
  j["size"] = o.size;
  j["frames"] = o.steps;
  j["grid_nodes"] = r.surface().grid().nodeCount();
  j["triangles"] = res[0].stats.triangles;
  j["blocks"] = res[0].stats.blocks;
  j["occupied_blocks"] = res[0].stats.occupied;
  const char* names[2] = {"with_occupancy", "without_occupancy"};
  for (int p = 0; p < 2; ++p)
    j[names[p]] = {{"splat_s", median(res[p].splat)}, {"occupancy_s", median(res[p].occupancy)},
                   {"march_s", median(res[p].march)}, {"surface_s", median(res[p].surface)},
                   {"shading_s", median(res[p].shading)}, {"frame_s", median(res[p].frame)},
                   {"find_iso_cubes_s", median(res[p].find)}, {"iso_cubes", res[p].isoCubes}};
  j["speedup_finding_iso_cubes"] = median(res[1].find) / std::max(median(res[0].find), 1e-12);
  j["speedup_isosurface_step"] = median(res[1].surface) / std::max(median(res[0].surface), 1e-12);
  if (o.json) {
    std::cout << j.dump(2) << "\n";
    return kExitOk;
  }
  std::printf("render bench %s: %zu particles, %s, %ld frames, grid %zu nodes, %ld of %ld blocks occupied, %ld triangles\n",
              o.scene.c_str(), frame.particles(), o.size.c_str(), o.steps, r.surface().grid().nodeCount(),
              res[0].stats.occupied, res[0].stats.blocks, res[0].stats.triangles);
  std::printf("  median seconds per frame   splat      occupancy  march      shading    frame     | find iso-cubes (count)\n");
  for (int p = 0; p < 2; ++p)
    std::printf("  %-24s %10.5f %10.5f %10.5f %10.5f %10.5f | %10.5f (%ld)\n", names[p], median(res[p].splat),
                median(res[p].occupancy), median(res[p].march), median(res[p].shading), median(res[p].frame),
                median(res[p].find), res[p].isoCubes);
  std::printf("occupancy speed-up: finding iso-cubes %.1fx, whole isosurface step %.1fx (paper: 20x and 3x)\n",
              double(j["speedup_finding_iso_cubes"]), double(j["speedup_isosurface_step"]));
  std::printf("(each step waited for with glFinish and timed on the wall clock; on llvmpipe the GPU is the CPU)\n");
  return kExitOk;
}

// The paper's Table 1 (seconds per step on a 2.4 GHz 4-core Q6600) beside ours for the same
// scenes at the paper's particle counts.
int benchPaper(const BenchOptions& o) {
  struct Row {
    const char* scene;
    double particles, sph, erosion, boundary;
  };
  const Row paper[] = {{"canyon", 136000, 0.33, 0.39, 0.66},
                       {"lake", 90000, 0.31, 0.17, 0.42},
                       {"waterfall", 650000, 1.25, 1.05, 2.20}};
  const int threads = omp_get_max_threads();
  json rows = json::array();
  for (const Row& r : paper) {
    Scene scene = loadScene(r.scene, o.scale, 0, o.sets);
    World w(scene.desc);
    std::vector<double> g[3], total;
    size_t particles = 0;
    RunEnd end = runSteps(w, o.warmup);
    const long steps = timedSteps(o.steps, w);
    if (end.ok())
      end = runSteps(w, steps, [&](const StepRecord& r) {
        total.push_back(r.seconds);
        for (int k = 0; k < 3; ++k) g[k].push_back(r.groupSeconds[size_t(k)]);
        particles += w.fluid().size();
      });
    if (!end.ok()) return stepFailure(end, r.scene);
    const double n = double(particles) / double(steps);
    auto windowed = [&](const std::vector<double>& v) { return median(windowMeans(v, exchangeEvery(w))); };
    const double ours[3] = {windowed(g[int(Table1Group::kSph)]), windowed(g[int(Table1Group::kErosion)]),
                            windowed(g[int(Table1Group::kBoundary)])};
    const double paperTotal = r.sph + r.erosion + r.boundary, oursTotal = ours[0] + ours[1] + ours[2];
    rows.push_back({{"scene", r.scene},
                    {"paper", {{"particles", r.particles}, {"sph_s", r.sph}, {"erosion_s", r.erosion},
                               {"boundary_s", r.boundary}, {"cores", 4},
                               {"particle_steps_per_second_per_core", r.particles / paperTotal / 4}}},
                    {"ours", {{"particles", long(n + 0.5)}, {"sph_s", ours[0]}, {"erosion_s", ours[1]},
                              {"boundary_s", ours[2]}, {"step_s", windowed(total)}, {"cores", threads},
                              {"particle_steps_per_second_per_core", n / oursTotal / threads}}}});
  }
  if (o.json) {
    std::cout << json{{"threads", threads}, {"steps", o.steps}, {"rows", rows}}.dump(2) << "\n";
    return kExitOk;
  }
  std::printf("Table 1 side by side: median seconds per step over %ld steps (after %ld warm-up)\n", o.steps, o.warmup);
  std::printf("paper: Intel Q6600, 4 cores at 2.4 GHz (2009); ours: %d threads on this machine\n\n", threads);
  std::printf("%-10s %9s %9s | %7s %7s | %7s %7s | %7s %7s | %7s %7s | %10s %10s\n", "scene", "particles",
              "(paper)", "SPH", "paper", "erosion", "paper", "bound.", "paper", "total", "paper", "p-s/s/core", "paper");
  for (const auto& r : rows) {
    const auto& a = r["ours"];
    const auto& b = r["paper"];
    const double ta = double(a["sph_s"]) + double(a["erosion_s"]) + double(a["boundary_s"]);
    const double tb = double(b["sph_s"]) + double(b["erosion_s"]) + double(b["boundary_s"]);
    std::printf("%-10s %9ld %9.0f | %7.3f %7.2f | %7.3f %7.2f | %7.3f %7.2f | %7.3f %7.2f | %10.0f %10.0f\n",
                std::string(r["scene"]).c_str(), long(a["particles"]), double(b["particles"]),
                double(a["sph_s"]), double(b["sph_s"]), double(a["erosion_s"]), double(b["erosion_s"]),
                double(a["boundary_s"]), double(b["boundary_s"]), ta, tb,
                double(a["particle_steps_per_second_per_core"]), double(b["particle_steps_per_second_per_core"]));
  }
  std::printf("\nratio paper / ours (total seconds per step; per core):\n");
  for (const auto& r : rows) {
    const auto& a = r["ours"];
    const auto& b = r["paper"];
    const double ta = double(a["sph_s"]) + double(a["erosion_s"]) + double(a["boundary_s"]);
    const double tb = double(b["sph_s"]) + double(b["erosion_s"]) + double(b["boundary_s"]);
    std::printf("  %-10s %.1fx faster per step, %.1fx per core\n", std::string(r["scene"]).c_str(), tb / ta,
                double(a["particle_steps_per_second_per_core"]) / double(b["particle_steps_per_second_per_core"]));
  }
  return kExitOk;
}

// Engine throughput with the window open (drawing every frame it can) and with no window, the
// same scene and time each.
int benchWindow(const BenchOptions& o, const Scene& scene) {
  double alone = 0;
  {
    SimulationWorker worker(scene.spec);
    while (!worker.poll()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const long s0 = worker.latest().frame.step;
    const auto t0 = std::chrono::steady_clock::now();
    std::this_thread::sleep_for(std::chrono::duration<double>(o.seconds));
    while (!worker.poll()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    alone = double(worker.latest().frame.step - s0) /
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  AppOptions a;
  if (!o.size.empty()) std::tie(a.width, a.height) = parseSize(o.size, 16);
  a.quitAfterSeconds = o.seconds;
  AppOptions::Stats st;
  a.stats = &st;
  runApp(scene.spec, a);
  const double windowed = double(st.steps) / st.seconds;
  // The frames after the first second (the first ones open the window and find the level).
  std::vector<double> frames;
  double at = 0;
  for (double t : st.frameSeconds) {
    if (at >= 1.0) frames.push_back(t);
    at += t;
  }
  if (frames.empty()) frames = st.frameSeconds;
  std::sort(frames.begin(), frames.end());
  auto quantile = [&](double q) { return frames.empty() ? 0.0 : frames[size_t(q * double(frames.size() - 1))]; };
  json j = {{"scene", o.scene}, {"particles", scene.desc.particles.size()}, {"seconds", o.seconds},
            {"threads", omp_get_max_threads()}, {"window", std::to_string(a.width) + "x" + std::to_string(a.height)},
            {"steps_per_second_no_window", alone}, {"steps_per_second_with_window", windowed},
            {"window_frames_per_second", double(st.frames) / st.seconds},
            {"frame_seconds_median", frames.empty() ? 0.0 : median(frames)}, {"frame_seconds_p95", quantile(0.95)},
            {"frame_seconds_max", frames.empty() ? 0.0 : frames.back()},
            {"surface_rebuilds_per_second", double(st.rebuilds) / st.seconds},
            {"surface_frames_fraction", double(st.surfaceFrames) / double(std::max(st.frames, 1L))},
            {"quality_level_changes", st.levelChanges},
            {"water_quality", st.quality}, {"ratio", windowed / std::max(alone, 1e-12)}};
  if (o.json) {
    std::cout << j.dump(2) << "\n";
    return kExitOk;
  }
  std::printf("engine steps per second, %s (%zu particles), %.0f s each: no window %.1f, window open %.1f "
              "(%.0f%%)\nthe %dx%d window drew %.1f frames/s (frame median %.0f ms, 95%% within %.0f ms, "
              "longest %.0f ms), the water surface rebuilt %.1f times a second and drawn in %.0f%% of the frames, "
              "%ld changes of level; water quality %s\n",
              o.scene.c_str(), scene.desc.particles.size(), o.seconds, alone, windowed, 100 * windowed / alone,
              a.width, a.height, double(st.frames) / st.seconds, 1e3 * double(j["frame_seconds_median"]), 1e3 * quantile(0.95),
              1e3 * double(j["frame_seconds_max"]), double(st.rebuilds) / st.seconds,
              100 * double(j["surface_frames_fraction"]), st.levelChanges, st.quality.c_str());
  return kExitOk;
}

// What the timed steps of one world add up to: per pass and Table 1 group, the totals, the
// water's time they covered and the solves' iterations; the medians are of windows of K steps
// (windowMeans).
struct StepTally {
  std::vector<std::vector<double>> perPass = std::vector<std::vector<double>>(size_t(Pass::kCount));
  std::vector<double> total, groups[4];
  double particles = 0;
  long window = 1;  ///< K (erosion.exchange_every): the medians are of windows of K steps
  // Wall seconds per simulated second (all the timed steps, not a median: a solver that takes
  // fewer, longer steps is judged on the water's time), and the solves' iterations.
  double wall = 0, simulated = 0, densityError = 0;
  long steps = 0, densityIterations = 0, divergenceIterations = 0;

  void add(const StepRecord& r, const World& w) {
    window = exchangeEvery(w);
    total.push_back(r.seconds);
    for (size_t p = 0; p < perPass.size(); ++p) perPass[p].push_back(r.passSeconds[p]);
    for (int k = 0; k < 4; ++k) groups[k].push_back(r.groupSeconds[size_t(k)]);
    particles += double(w.fluid().size());
    wall += r.seconds, simulated += r.stats.dt, densityError += r.stats.density_error;
    densityIterations += r.stats.density_iterations, divergenceIterations += r.stats.divergence_iterations;
    ++steps;
  }

  // The medians of each pass and group, the speed per core and the memory per particle.
  json report(const std::string& name, const Scene& scene, const World& world, bool erosion) const {
    const int threads = omp_get_max_threads();
    const double n = double(std::max(steps, 1L));
    const double meanParticles = particles / n;
    auto median = [&](const std::vector<double>& v) { return scour::median(windowMeans(v, window)); };
    const double tTotal = median(total);
    const double tSph = median(groups[int(Table1Group::kSph)]);
    json j;
    j["scene"] = name;
    j["particles"] = long(meanParticles + 0.5);
    j["spacing"] = scene.desc.params.spacing;  // Δs
    j["terrain_cell"] = std::max(scene.desc.terrain.dx(), scene.desc.terrain.dz());
    j["boundary_particles"] = world.boundary().size();
    j["erosion_effects"] = erosion || scene.desc.effects.erosion;
    j["threads"] = threads;
    j["steps"] = steps;
    j["exchange_every"] = window;
    json sps = {{"total", tTotal}};
    for (size_t p = 0; p < perPass.size(); ++p)
      if (world.passCalls()[p] > 0) sps[passName(Pass(p))] = median(perPass[p]);
    j["seconds_per_step"] = sps;
    j["table1"] = {{"sph", tSph},
                   {"erosion", median(groups[int(Table1Group::kErosion)])},
                   {"boundary", median(groups[int(Table1Group::kBoundary)])}};
    j["particle_steps_per_second_per_core"] = meanParticles / tTotal / threads;
    j["sph_particle_steps_per_second_per_core"] = meanParticles / tSph / threads;
    j["memory_bytes_per_particle"] = double(world.memoryBytes()) / meanParticles;
    j["neighbors_per_particle"] =
        double(world.neighbors().totalPairs()) / double(std::max<size_t>(1, world.fluid().size()));
    j["ratio"] = (double(j["table1"]["erosion"]) + double(j["table1"]["boundary"])) / std::max(tSph, 1e-300);
    j["solver"] = scene.desc.params.solver == FluidSolver::kDfsph ? "dfsph" : "wcsph";
    j["simulated_seconds"] = simulated;
    j["wall_seconds"] = wall;
    j["mean_dt"] = simulated / n;
    j["wall_seconds_per_simulated_second"] = wall / std::max(simulated, 1e-300);
    j["density_iterations_per_step"] = double(densityIterations) / n;
    j["divergence_iterations_per_step"] = double(divergenceIterations) / n;
    j["mean_density_error"] = densityError / n;
    return j;
  }
};

std::unique_ptr<World> makeWorld(const std::string& name, const Scene& scene) {
  try {
    return std::make_unique<World>(scene.desc);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("scene '") + name + "': " + e.what());
  }
}

// One scene's step: the median seconds of each pass and Table 1 group over o.steps steps after
// o.warmup, the speed per core and the memory per particle. On a failed step: *code, and null.
json measureSteps(const BenchOptions& o, const std::string& name, const Scene& scene, int* code) {
  std::unique_ptr<World> world = makeWorld(name, scene);
  StepTally tally;
  RunEnd end = runSteps(*world, o.warmup);
  if (end.ok()) end = runSteps(*world, timedSteps(o.steps, *world), [&](const StepRecord& r) { tally.add(r, *world); });
  if (!end.ok()) {
    *code = stepFailure(end, name);
    return {};
  }
  return tally.report(name, scene, *world, o.erosion);
}

// The same scene under two or more settings (`--side-by-side "key=value ..."`, each on top of
// --set), stepped in turn in one process so that the machine's drift hits them alike, over the
// same stretch of the water's time: each takes o.warmup steps and catches up with the furthest,
// then the first takes o.steps timed steps while every other one, always stepping whichever is
// behind, follows it to the same simulated time. What counts is wall seconds per simulated
// second: a solver that takes fewer, longer steps is judged on the water's time.
int benchSideBySide(const BenchOptions& o) {
  struct Config {
    std::string label;
    Scene scene;
    std::unique_ptr<World> world;
    StepTally tally;
  };
  if (o.sideBySide.size() < 2)
    throw InputError("--side-by-side: give at least two settings to compare (one given)");
  std::vector<Config> configs;
  for (const std::string& spec : o.sideBySide) {
    std::vector<std::string> sets = o.sets;
    std::istringstream words(spec);
    for (std::string w; words >> w;) {
      // Each word is refused under its own flag, not as a --set.
      const size_t eq = w.find('=');
      if (eq == std::string::npos) throw InputError("--side-by-side: '" + w + "' has no key=value");
      SimParams check;
      const std::string err = setParam(check, w.substr(0, eq), w.substr(eq + 1));
      if (!err.empty()) throw InputError("--side-by-side '" + spec + "': " + err);
      sets.push_back(w);
    }
    Config c{spec, loadScene(o.scene, o.scale, o.particles, sets), nullptr, {}};
    c.world = makeWorld(o.scene, c.scene);
    configs.push_back(std::move(c));
  }
  RunEnd end;
  auto step = [&](Config& c, bool timed) {
    end = runSteps(*c.world, 1, [&](const StepRecord& r) {
      if (timed) c.tally.add(r, *c.world);
    });
    return end.ok();
  };
  auto failed = [&](const Config& c) { return stepFailure(end, o.scene + " (" + c.label + ")"); };
  for (long s = 0; s < o.warmup; ++s)
    for (Config& c : configs)
      if (!step(c, false)) return failed(c);
  double start = 0;
  for (const Config& c : configs) start = std::max(start, c.world->time());
  for (Config& c : configs)
    while (c.world->time() < start)
      if (!step(c, false)) return failed(c);
  // The first takes o.steps timed steps; the others follow it through the same water's time.
  auto done = [&](size_t k) {
    const bool firstDone = configs[0].tally.steps >= o.steps;
    return k == 0 ? firstDone : firstDone && configs[k].world->time() >= configs[0].world->time();
  };
  for (;;) {
    size_t next = configs.size();
    for (size_t k = 0; k < configs.size(); ++k)
      if (!done(k) && (next == configs.size() || configs[k].world->time() < configs[next].world->time()))
        next = k;
    if (next == configs.size()) break;
    if (!step(configs[next], true)) return failed(configs[next]);
  }
  json rows = json::array();
  const double base = configs[0].tally.wall / std::max(configs[0].tally.simulated, 1e-300);
  for (const Config& c : configs) {
    json j = c.tally.report(o.scene, c.scene, *c.world, false);
    j["settings"] = c.label;
    j["against_first"] = double(j["wall_seconds_per_simulated_second"]) / base;
    rows.push_back(std::move(j));
  }
  if (o.json) {
    std::cout << json{{"scene", o.scene}, {"scale", o.scale}, {"threads", omp_get_max_threads()},
                      {"warmup", o.warmup}, {"rows", rows}}.dump(2) << "\n";
    return kExitOk;
  }
  std::printf("%s side by side: %d threads, stepped in turn over the same %.4g simulated seconds "
              "(after %ld warm-up steps each)\n",
              o.scene.c_str(), omp_get_max_threads(), double(rows[0]["simulated_seconds"]), o.warmup);
  int width = 8;
  for (const Config& c : configs) width = std::max(width, int(c.label.size()));
  std::printf("%-*s %9s %6s %8s %8s %12s %9s %8s %8s %9s\n", width, "settings", "particles", "steps", "dt ms",
              "wall s", "wall s/sim s", "vs first", "dens it", "div it", "dens err");
  for (const json& r : rows)
    std::printf("%-*s %9ld %6ld %8.3f %8.2f %12.2f %9.2f %8.1f %8.1f %9.2e\n", width,
                std::string(r["settings"]).c_str(), long(r["particles"]), long(r["steps"]),
                1e3 * double(r["mean_dt"]), double(r["wall_seconds"]),
                double(r["wall_seconds_per_simulated_second"]), double(r["against_first"]),
                double(r["density_iterations_per_step"]), double(r["divergence_iterations_per_step"]),
                double(r["mean_density_error"]));
  return kExitOk;
}

// The paper's three presets at the scales users run (the window: 0.1–0.3), each measured
// `repeat` times in turn (scene after scene, so the machine's drift hits all alike); each figure
// is the median over the repeats of the per-run medians.
int benchPresets(const BenchOptions& o) {
  const int threads = omp_get_max_threads();
  const char* const names[] = {"canyon", "lake", "waterfall"};
  struct Cell {
    std::string name;
    double scale;
    std::vector<json> runs;
  };
  std::vector<Cell> cells;
  for (const char* n : names)
    for (double sc : o.scales) cells.push_back({n, sc, {}});
  for (int r = 0; r < o.repeat; ++r)
    for (Cell& c : cells) {
      const Scene scene = loadScene(c.name, c.scale, 0, o.sets);
      int code = kExitOk;
      json j = measureSteps(o, c.name, scene, &code);
      if (j.is_null()) return code;
      c.runs.push_back(std::move(j));
    }
  auto med = [](const Cell& c, auto get) {
    std::vector<double> v;
    for (const json& j : c.runs) v.push_back(get(j));
    return median(v);
  };
  json rows = json::array();
  for (const Cell& c : cells) {
    json row = {{"scene", c.name}, {"scale", c.scale}, {"runs", c.runs.size()},
                {"particles", c.runs.front()["particles"]}};
    for (const char* g : {"sph", "erosion", "boundary"})
      row[std::string(g) + "_s"] = med(c, [&](const json& j) { return double(j["table1"][g]); });
    row["step_s"] = med(c, [](const json& j) { return double(j["seconds_per_step"]["total"]); });
    row["ratio"] = med(c, [](const json& j) { return double(j["ratio"]); });
    row["particle_steps_per_second_per_core"] =
        med(c, [](const json& j) { return double(j["particle_steps_per_second_per_core"]); });
    row["sph_particle_steps_per_second_per_core"] =
        med(c, [](const json& j) { return double(j["sph_particle_steps_per_second_per_core"]); });
    row["memory_bytes_per_particle"] = med(c, [](const json& j) { return double(j["memory_bytes_per_particle"]); });
    row["wall_seconds_per_simulated_second"] =
        med(c, [](const json& j) { return double(j["wall_seconds_per_simulated_second"]); });
    row["density_iterations_per_step"] = med(c, [](const json& j) { return double(j["density_iterations_per_step"]); });
    rows.push_back(row);
  }
  if (o.json) {
    std::cout << json{{"threads", threads}, {"steps", o.steps}, {"warmup", o.warmup}, {"repeat", o.repeat},
                      {"rows", rows}}.dump(2) << "\n";
    return kExitOk;
  }
  std::printf("presets: median seconds per step over %ld steps (after %ld warm-up), %d threads, "
              "median of %d run(s)\n", o.steps, o.warmup, threads, o.repeat);
  std::printf("%-10s %5s %9s | %9s %9s %9s | %11s | %12s %12s | %9s\n", "scene", "scale", "particles", "SPH s",
              "erosion s", "boundary s", "(er+bd)/SPH", "p-steps/s/c", "SPH alone", "bytes/p");
  for (const json& r : rows)
    std::printf("%-10s %5.2f %9ld | %9.5f %9.5f %9.5f | %10.0f%% | %12.0f %12.0f | %9.0f\n",
                std::string(r["scene"]).c_str(), double(r["scale"]), long(r["particles"]), double(r["sph_s"]),
                double(r["erosion_s"]), double(r["boundary_s"]), 100 * double(r["ratio"]),
                double(r["particle_steps_per_second_per_core"]), double(r["sph_particle_steps_per_second_per_core"]),
                double(r["memory_bytes_per_particle"]));
  return kExitOk;
}

int bench(const BenchOptions& o) {
  setThreads(o.threads);
  if (o.paper) return benchPaper(o);
  if (o.presets) return benchPresets(o);
  if (!o.sideBySide.empty()) return benchSideBySide(o);
  if (o.withWindow) return benchWindow(o, loadScene(o.scene, o.scale, o.particles, o.sets));
  Scene scene = loadScene(o.scene, o.scale, o.particles, o.sets);
  if (o.ablation) return ablation(o, scene);
  if (o.render) return benchRender(o, scene);
  if (o.erosion) {
    // Every sediment pass at full work: all effects on, and every particle already carrying
    // sediment (so no pair is skipped as empty).
    Effects& e = scene.desc.effects;
    e.erosion = e.settling = e.diffusion = e.deposition = true;
    scene.desc.concentration.assign(scene.desc.particles.size(), 0.01);
  }
  int code = kExitOk;
  const json j = measureSteps(o, o.scene, scene, &code);
  if (j.is_null()) return code;
  if (o.json) {
    std::cout << j.dump(2) << "\n";
    return kExitOk;
  }
  const long every = long(j["exchange_every"]);
  std::printf("scene %s: %ld particles, %d threads, %ld steps (median seconds per step%s)\n",
              o.scene.c_str(), long(j["particles"]), int(j["threads"]), long(j["steps"]),
              every > 1 ? (", over windows of " + std::to_string(every) + " steps: the bed's work every " +
                           std::to_string(every)).c_str()
                        : "");
  for (auto& [k, v] : j["seconds_per_step"].items()) std::printf("  %-22s %10.6f\n", k.c_str(), double(v));
  std::printf("Table 1 groups: SPH %.6f  erosion %.6f  boundary %.6f  ((erosion + boundary) / SPH = %.0f%%)\n",
              double(j["table1"]["sph"]), double(j["table1"]["erosion"]),
              double(j["table1"]["boundary"]), 100.0 * double(j["ratio"]));
  std::printf("particle-steps/s/core: %.0f (SPH part alone: %.0f)\n",
              double(j["particle_steps_per_second_per_core"]),
              double(j["sph_particle_steps_per_second_per_core"]));
  std::printf("memory: %.0f bytes/particle; %.1f neighbors/particle\n",
              double(j["memory_bytes_per_particle"]), double(j["neighbors_per_particle"]));
  std::printf("solver %s: mean step %.3g ms, %.1f wall seconds per simulated second",
              std::string(j["solver"]).c_str(), 1e3 * double(j["mean_dt"]),
              double(j["wall_seconds_per_simulated_second"]));
  if (j["solver"] == "dfsph")
    std::printf("; %.1f density and %.1f divergence iterations per step",
                double(j["density_iterations_per_step"]), double(j["divergence_iterations_per_step"]));
  std::printf("\n");
  return kExitOk;
}

}  // namespace

Command addBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* c = app.add_subcommand("bench", "Time the step: median seconds per pass");
  c->add_option("scene", o->scene, "Built-in scene name (default: block)");
  c->add_option("--particles", o->particles, "Approximate particle count (block scene)")
      ->check(kPositive);
  c->add_option("--steps", o->steps, "Timed steps")->check(kPositive);
  c->add_option("--warmup", o->warmup, "Untimed steps first")->check(CLI::NonNegativeNumber);
  c->add_option("--threads", o->threads, "OpenMP threads (default: all cores)")->check(kPositive);
  c->add_option("--scale", o->scale, "Scale the preset's particle count")->check(kPositive);
  c->add_option("--set", o->sets, "Override a parameter: key=value (repeatable)");
  c->add_flag("--json", o->json, "One JSON object on stdout");
  c->add_flag("--erosion", o->erosion,
              "Turn on erosion, settling, diffusion and deposition, with C = 0.01 everywhere");
  c->add_flag("--render", o->render,
              "Time the renderer instead: splat, occupancy, march, shading, with and without the occupancy grid");
  c->add_option("--size", o->size, "Picture size for --render (default 960x540), window size for --with-window (default 1280x720)");
  c->add_flag("--with-window", o->withWindow,
              "Engine steps per second with the window open and with none (needs a display)");
  c->add_option("--seconds", o->seconds, "How long each --with-window phase runs (default 5)")->check(kPositive);
  c->add_flag("--paper", o->paper,
              "The paper's Table 1 beside ours: canyon, lake and waterfall at the paper's counts");
  c->add_flag("--presets", o->presets,
              "canyon, lake and waterfall at each of --scales: the Table 1 groups, their ratio, speed per core, memory");
  c->add_option("--scales", o->scales, "Scales for --presets (default 0.1 0.3 1)")->check(kPositive)->delimiter(',');
  c->add_option("--repeat", o->repeat, "Runs of each --presets scene, in turn; the medians are reported")
      ->check(kPositive);
  c->add_option("--side-by-side", o->sideBySide,
                 "Settings to compare in one run, each 'key=value ...' on top of --set (repeat, at least "
                 "twice): stepped in turn over the same simulated time, wall seconds per simulated second")
      ->each([](const std::string& v) {
        if (v.find('=') == std::string::npos)
          throw CLI::ValidationError("'" + v + "' has no key=value");
      });
  c->add_flag("--ablation", o->ablation,
              "Compare all effects, erosion off and SPH only, stepped in turn");
  return [o] { return bench(*o); };
}

}  // namespace scour
