#include "study/study.h"

#include "engine/step_driver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>

#include "engine/sediment.h"
#include "scene/presets.h"
#include "study/measures.h"

namespace scour {

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kInf = std::numeric_limits<double>::infinity();

double seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// One run of a scene: steps `until` says no more, or an invariant breaks. `each` sees every step.
struct Run {
  double wall = 0;
  std::string status = "ok";
};
template <class Until, class Each>
Run drive(World& w, Until&& until, Each&& each) {
  Run r;
  const auto start = Clock::now();
  const RunEnd end = runWhile(w, [&] { return !until(); }, [&](const StepRecord&) { each(); });
  if (end.status == RunEnd::Status::kInvariantViolated) r.status = "unstable: " + end.message;
  else if (!end.ok()) throw std::runtime_error(end.message);
  r.wall = seconds(start);
  return r;
}

StudyRow row(const std::string& study, const std::string& reference, const std::string& choice,
             double error, const Run& run, const World& w) {
  StudyRow r;
  r.study = study;
  r.reference = reference;
  r.choice = choice;
  r.error = run.status == "ok" ? error : kInf;
  r.wall_seconds = run.wall;
  r.simulated_seconds = w.time();
  r.cost = w.time() > 0 ? run.wall / w.time() : kInf;
  r.particles = long(w.fluid().size());
  r.status = run.status;
  return r;
}

// --- references -------------------------------------------------------------------------------

// Martin & Moyce (1952), a = 2.25 in: (T, Z) with T = t √(2g/a), Z = front / a.
const std::vector<std::pair<double, double>> kMartinMoyce = {
    {0.832, 1.217}, {1.219, 1.474}, {1.997, 2.292}, {2.547, 2.995},
    {3.345, 4.134}, {4.034, 4.944}, {4.418, 5.881}, {5.091, 6.980}};

// The mean compression of the water, max(ρ/ρ0 − 1, 0) averaged over the particles: what
// DFSPH's fluid.max_density_error bounds, read from each solver's own density.
double meanCompression(const World& w) {
  const Fluid& f = w.fluid();
  const double rho0 = w.params().rest_density;
  double sum = 0;
  for (size_t i = 0; i < f.size(); ++i) sum += std::max(double(f.rho[i]) / rho0 - 1.0, 0.0);
  return f.size() ? sum / double(f.size()) : 0.0;
}

// The dam break's front against Martin & Moyce; *compression (when given): the mean compression
// averaged over every step of the run.
StudyRow damBreak(const std::string& study, const std::string& choice, SceneSpec spec,
                  double tMax, double* compression = nullptr) {
  const double a = 0.05715;
  World w(buildScene(spec).desc);
  const double tScale = std::sqrt(2.0 * w.params().gravity / a);
  std::vector<std::pair<double, double>> front{{0.0, 1.0}};
  // The water's edge: the foremost particle's centre plus half a spacing (the column starts at
  // Z = 1 exactly; a particle centre would lag the edge by Δs/2, flattering coarse runs).
  const double half = 0.5 * spec.params.spacing;
  auto xmax = [&] {
    float m = 0;
    for (const auto& x : w.fluid().x) m = std::max(m, x.x());
    return double(m) + half;
  };
  front.back().second = xmax() / a;
  double squeezed = 0;
  long steps = 0;
  const Run run = drive(w, [&] { return w.time() * tScale > tMax + 0.2; }, [&] {
    front.emplace_back(w.time() * tScale, xmax() / a);
    if (compression) squeezed += meanCompression(w), ++steps;
  });
  if (compression) *compression = run.status == "ok" && steps ? squeezed / double(steps) : kInf;
  double worst = 0;
  for (auto [T, Z] : kMartinMoyce) {
    // From T = 1.2 on, as ../shared/tools/dambreak-front.py does: the first point (T = 0.83)
    // is the experiment's gate still opening.
    if (T < 1.2 || T > tMax) continue;
    auto it = std::lower_bound(front.begin(), front.end(), std::make_pair(T, -1e300));
    if (it == front.begin() || it == front.end()) {
      worst = kInf;
      continue;
    }
    const auto [T1, Z1] = *it;
    const auto [T0, Z0] = *(it - 1);
    const double z = Z0 + (Z1 - Z0) * (T - T0) / (T1 - T0);
    worst = std::max(worst, std::abs(z - Z) / Z);
  }
  return row(study, "dam-break front", choice, worst, run, w);
}

// *compression (when given): the mean compression averaged over the same samples as the pressure.
StudyRow hydrostatic(const std::string& study, const std::string& choice, SceneSpec spec,
                     double settle, double average, double* compression = nullptr) {
  const Scene s = buildScene(spec);
  const double ds = spec.params.spacing, g = spec.params.gravity, rho0 = spec.params.rest_density;
  const Heightfield& hf = s.desc.terrain;
  const double area = (hf.xMax() - hf.x0()) * (hf.zMax() - hf.z0());
  const double H = double(s.desc.particles.size()) * ds * ds * ds / area;
  World w(s.desc);
  const int layers = int(std::ceil(H / ds)) + 2;
  std::vector<double> sumP(layers, 0), sumY(layers, 0);
  std::vector<long> count(layers, 0);
  double squeezed = 0;
  long samples = 0;
  const Run run = drive(w, [&] { return w.time() >= settle + average; }, [&] {
    if (w.time() < settle || w.steps() % 10) return;
    squeezed += meanCompression(w), ++samples;
    const Fluid& f = w.fluid();
    for (size_t i = 0; i < f.size(); ++i) {
      const int b = int(f.x[i].y() / ds);
      if (b < 0 || b >= layers) continue;
      sumP[b] += f.p[i], sumY[b] += f.x[i].y(), ++count[b];
    }
  });
  double worst = 0;
  for (int b = 0; b < layers; ++b) {
    if (count[b] == 0) continue;
    const double y = sumY[b] / count[b], p = sumP[b] / count[b];
    if (y > 0.8 * H) continue;
    const double expect = rho0 * g * (H - y);
    worst = std::max(worst, std::abs(p / expect - 1.0));
  }
  if (compression) *compression = run.status == "ok" && samples ? squeezed / double(samples) : kInf;
  return row(study, "hydrostatic pressure", choice, worst, run, w);
}

// The settling lattice: the centroid's speed against |v_s| (least squares away from the top and
// the floor), and the sediment the scheme made or lost, relative to what there was.
std::vector<StudyRow> settling(const std::string& choice, SettlingAdvection advection) {
  SceneSpec spec = presetSpec("settling");
  spec.params.advection = advection;
  World w(buildScene(spec).desc);
  const double vs = w.params().settlingSpeed(), h = w.params().support();
  const double s0 = suspendedSediment(w);
  const Fluid& f = w.fluid();
  float yTop = 0;
  for (size_t i = 0; i < f.size(); ++i)
    if (f.sed[i] > 0) yTop = f.x[i].y();
  auto centroid = [&] { return sedimentCentroid(w).y(); };
  std::vector<std::pair<double, double>> samples;
  double budget = 0;
  const Run run = drive(w, [&] { return centroid() <= 3 * h || w.time() > 60.0; }, [&] {
    budget = std::max(budget, std::abs(suspendedSediment(w) - s0) / s0);
    if (centroid() < yTop - h) samples.emplace_back(w.time(), centroid());
  });
  const double speed = samples.size() > 2 ? -leastSquaresSlope(samples) : 0.0;
  return {row("advection", "settling speed", choice, std::abs(speed / vs - 1.0), run, w),
          row("advection", "soil budget", choice, budget, run, w)};
}

// The diffusion lattice: dσ²/dt over 0.4 s once the pulse covers 1.5 h (or after 1 s, for a form
// that hardly spreads it), against 2D.
StudyRow diffusion(const std::string& choice, DiffusionForm form) {
  SceneSpec spec = presetSpec("diffusion");
  spec.params.diffusion_form = form;
  World w(buildScene(spec).desc);
  const double D = w.params().diffusion, h = w.params().support();
  const Eigen::Vector3d c0 = sedimentCentroid(w);
  auto variance = [&] { return sedimentVariance(w, c0); };
  double t1 = -1;
  Eigen::Vector3d v1 = Eigen::Vector3d::Zero();
  const Run run = drive(
      w, [&] { return t1 >= 0 && w.time() >= t1 + 0.4; },
      [&] {
        if (t1 < 0 && (variance().mean() >= std::pow(1.5 * h, 2) || w.time() >= 1.0))
          t1 = w.time(), v1 = variance();
      });
  const Eigen::Vector3d growth = (variance() - v1) / (w.time() - t1);
  return row("diffusion_form", "diffusion variance", choice, std::abs(growth.mean() / (2 * D) - 1),
             run, w);
}

// The kd-tree against the grid: the same steps of a scene, positions compared by particle id.
StudyRow neighborSearch(const std::string& choice, SceneSpec spec, long steps, NeighborSearch search,
                        const std::vector<Vec3f>* gridPositions, std::vector<Vec3f>* out) {
  spec.params.neighbor_search = search;
  World w(buildScene(spec).desc);
  long k = 0;
  const Run run = drive(w, [&] { return k >= steps; }, [&] { ++k; });
  const Fluid& f = w.fluid();
  std::vector<Vec3f> byId(f.size());
  for (size_t i = 0; i < f.size(); ++i)
    if (f.id[i] < byId.size()) byId[f.id[i]] = f.x[i];
  double worst = 0;
  if (gridPositions && gridPositions->size() == byId.size())
    for (size_t i = 0; i < byId.size(); ++i)
      worst = std::max(worst, double(((*gridPositions)[i] - byId[i]).norm()));
  if (out) *out = byId;
  StudyRow r = row("neighbor_search", "grid lists (" + std::to_string(f.size()) + " particles)",
                   choice, worst / spec.params.spacing, run, w);
  return r;
}

// --- the bed: what erosion made of the terrain --------------------------------------------------

// The settled height change of every vertex since the start, and the volume cut
// (measureTerrainChange).
struct BedChange {
  std::vector<double> dh;
  double eroded = 0;
};
BedChange bedChange(const World& w) {
  BedChange b;
  b.dh = w.heightChange();
  b.eroded = measureTerrainChange(b.dh, w.vertexArea()).eroded;
  return b;
}
// RMS of a − b over the vertices (b empty: of a).
double rms(const std::vector<double>& a, const std::vector<double>& b = {}) {
  double s = 0;
  for (size_t v = 0; v < a.size(); ++v) {
    const double d = a[v] - (b.empty() ? 0.0 : b[v]);
    s += d * d;
  }
  return a.empty() ? 0.0 : std::sqrt(s / double(a.size()));
}

std::string fmt(double v, int precision = 3);

// The geologic clock (model.md, "two clocks"): the valley river (the default scene of earlier
// versions) run to the same bed time at growing N, after the same spin-up at N = 1 (the same state at its end, bit for bit). Error: the
// RMS difference of the height change since the spin-up against N = 1's, over N = 1's RMS height
// change since the spin-up; cost: wall seconds per second of bed time.
std::vector<StudyRow> morphologicalFactor(bool quick) {
  SceneSpec base = presetSpec("valley", quick ? 0.25 : 1.0);
  const double spinup = quick ? 0.5 : 1.0, bedTime = quick ? 0.5 : 2.0;
  base.params.morphological_spinup = spinup;
  std::vector<StudyRow> rows;
  BedChange reference;
  for (double n : quick ? std::vector<double>{1, 10, 100} : std::vector<double>{1, 10, 100, 1000}) {
    SceneSpec s = base;
    s.params.morphological_factor = n;
    World w(buildScene(s).desc);
    std::vector<double> atSpinup;
    double markT = 0;  // the bed's time when the spin-up ended
    const Run run = drive(w, [&] { return w.morphologicalTime() >= spinup + bedTime - 1e-12; }, [&] {
      if (atSpinup.empty() && w.time() >= spinup) atSpinup = w.heightChange(), markT = w.morphologicalTime();
    });
    BedChange c = bedChange(w);
    // The last step can pass the target by up to N Δt of bed time: the change since the spin-up
    // is scaled back to the target's.
    const double reached = w.morphologicalTime() - markT;
    const double toTarget = reached > 0 ? (spinup + bedTime - markT) / reached : 1.0;
    if (atSpinup.size() == c.dh.size())
      for (size_t v = 0; v < c.dh.size(); ++v) c.dh[v] = (c.dh[v] - atSpinup[v]) * toTarget;
    if (n == 1) reference = c;
    // What the guard allowed, when it stepped in.
    const std::string choice = "N = " + fmt(n) +
                               (w.bedGuard().lowered > 0 ? " (guard: " + fmt(w.morphologicalFactor()) + ")" : "");
    StudyRow r = row("morphological_factor", "bed change (RMS)", choice, rms(c.dh, reference.dh) / rms(reference.dh),
                     run, w);
    r.simulated_seconds = w.morphologicalTime();
    r.cost = run.wall / r.simulated_seconds;
    rows.push_back(r);
  }
  return rows;
}

// The carved terrain against resolution: the valley river at four particle spacings for the
// same water time, against the finest: the eroded volume, and the RMS height change.
std::vector<StudyRow> erosionSpacing(bool quick) {
  const double t = quick ? 0.3 : 1.0;
  const std::vector<double> scales = quick ? std::vector<double>{0.125, 0.25, 0.5, 1.0}
                                           : std::vector<double>{0.25, 0.5, 1.0, 2.0};
  std::vector<std::tuple<std::string, Run, BedChange, double, long>> runs;
  for (double sc : scales) {
    const SceneSpec s = presetSpec("valley", sc);
    World w(buildScene(s).desc);
    const Run run = drive(w, [&] { return w.time() >= t - 1e-12; }, [] {});
    runs.emplace_back("Δs = " + fmt(s.params.spacing * 100) + " cm", run, bedChange(w), w.time(),
                      long(w.fluid().size()));
  }
  const BedChange& finest = std::get<2>(runs.back());
  std::vector<StudyRow> rows;
  for (const auto& [choice, run, c, time, particles] : runs) {
    for (int k = 0; k < 2; ++k) {
      StudyRow r;
      r.study = "erosion_spacing";
      r.reference = k == 0 ? "eroded volume" : "bed change (RMS)";
      r.choice = choice;
      r.error = run.status != "ok" ? kInf
                : k == 0       ? std::abs(c.eroded / finest.eroded - 1.0)
                               : rms(c.dh, finest.dh) / rms(finest.dh);
      r.wall_seconds = run.wall;
      r.simulated_seconds = time;
      r.cost = time > 0 ? run.wall / time : kInf;
      r.particles = particles;
      r.status = run.status;
      rows.push_back(r);
    }
  }
  return rows;
}

std::string fmt(double v, int precision) {
  if (std::isinf(v)) return "inf";
  std::ostringstream o;
  o << std::setprecision(precision) << v;
  return o.str();
}

}  // namespace

std::vector<StudyRow> runEngineStudies(const StudyOptions& o) {
  std::vector<StudyRow> rows;
  auto add = [&](StudyRow r) {
    if (o.log)
      o.log(r.study + " / " + r.reference + " / " + r.choice + ": error " + fmt(r.error) +
            ", " + fmt(r.wall_seconds, 2) + " s wall" + (r.status == "ok" ? "" : " — " + r.status));
    rows.push_back(std::move(r));
  };
  const double tMax = 5.0;  // Martin & Moyce's points up to T = 5
  auto damLabel = [](const SceneSpec& s) {
    return "Δs = a/" + fmt(0.05715 / s.params.spacing, 3);
  };

  // 1. Particle spacing: the dam break and the hydrostatic tank at four or more levels.
  const std::vector<double> damScales =
      o.quick ? std::vector<double>{0.06, 0.125, 0.3, 1.0} : std::vector<double>{0.06, 0.125, 0.3, 1.0, 3.4};
  for (double sc : damScales) {
    SceneSpec s = presetSpec("dambreak", sc);
    add(damBreak("spacing", damLabel(s), s, tMax));
  }
  // Spacings that divide the 0.2 m tank, so the water fills it and its depth is N Δs³ / area.
  const std::vector<double> tankSpacing = o.quick ? std::vector<double>{0.05, 0.04, 0.025, 0.02}
                                                  : std::vector<double>{0.05, 0.04, 0.025, 0.02, 0.0125};
  const double settle = o.quick ? 1.0 : 1.5, average = o.quick ? 0.3 : 0.5;
  for (double ds : tankSpacing) {
    SceneSpec s = presetSpec("hydrostatic");
    s.params.spacing = ds;
    add(hydrostatic("spacing", "Δs = " + fmt(ds * 100) + " cm", s, settle, average));
  }

  // 2. Time step: the paper's fixed 2 ms and smaller fixed steps against the adaptive CFL step.
  const SceneSpec damBase = presetSpec("dambreak", o.quick ? 0.3 : 1.0);
  const std::vector<double> fixed = o.quick ? std::vector<double>{0.002, 0.0001}
                                            : std::vector<double>{0.002, 0.0005, 0.0002, 0.0001};
  for (double dt : fixed) {
    SceneSpec s = damBase;
    s.params.fixed_dt = dt;
    add(damBreak("time_step", "fixed Δt = " + fmt(dt * 1000) + " ms", s, tMax));
  }
  const std::vector<double> cfls = o.quick ? std::vector<double>{0.4, 0.2}
                                           : std::vector<double>{0.4, 0.2, 0.1};
  for (double l : cfls) {
    SceneSpec s = damBase;
    s.params.cfl = l;
    add(damBreak("time_step", "CFL λ = " + fmt(l), s, tMax));
  }

  // 3. Equation of state: Tait against Müller's ideal gas.
  for (EquationOfState eos : {EquationOfState::kTait, EquationOfState::kIdealGas}) {
    const std::string name = eos == EquationOfState::kIdealGas ? "ideal gas" : "Tait";
    SceneSpec s = damBase;
    s.params.eos = eos;
    add(damBreak("eos", name, s, tMax));
    SceneSpec t = presetSpec("hydrostatic");
    t.params.spacing = o.quick ? 0.04 : 0.02;
    t.params.eos = eos;
    add(hydrostatic("eos", name, t, settle, average));
  }

  // 4. Neighbor search: our uniform grid against the paper's kd-tree (nanoflann), on the dam
  // break and on pools of growing size (the paper: "negligibly slower" under 50k particles).
  {
    // The dam break against Martin & Moyce with each search (after a few hundred steps the
    // splash amplifies the different summation order into visibly different particles, so
    // positions are compared on the pools, over a few steps).
    for (NeighborSearch search : {NeighborSearch::kGrid, NeighborSearch::kKdTree}) {
      SceneSpec s = damBase;
      s.params.neighbor_search = search;
      add(damBreak("neighbor_search", search == NeighborSearch::kKdTree ? "kd-tree" : "grid", s,
                   tMax));
    }
    std::vector<Vec3f> grid;
    for (long n : o.quick ? std::vector<long>{10000} : std::vector<long>{10000, 50000, 130000}) {
      SceneSpec b = presetSpec("block", 1.0, n);
      const long bsteps = o.quick ? 10 : 30;
      add(neighborSearch("grid", b, bsteps, NeighborSearch::kGrid, nullptr, &grid));
      add(neighborSearch("kd-tree", b, bsteps, NeighborSearch::kKdTree, &grid, nullptr));
    }
  }

  // 5. Sediment advection: donor–acceptor against the naive symmetric gradient.
  for (auto& r : settling("donor–acceptor", SettlingAdvection::kDonorAcceptor)) add(r);
  for (auto& r : settling("naive gradient", SettlingAdvection::kNaiveGradient)) add(r);

  // 6. Diffusion: the dimensionally consistent form against eq. (19) as printed.
  add(diffusion("consistent", DiffusionForm::kConsistent));
  add(diffusion("as printed", DiffusionForm::kPrinted));

  // 7. The geologic clock: what the morphological factor buys and costs.
  for (auto& r : morphologicalFactor(o.quick)) add(r);
  // 8. The carved terrain against particle spacing.
  for (auto& r : erosionSpacing(o.quick)) add(r);

  // 9. The pressure solver: WCSPH's equation of state against DFSPH at two density-error
  // tolerances, on the front, the tank and the water's mean compression in each.
  {
    struct Choice {
      const char* name;
      FluidSolver solver;
      double tolerance;
    };
    for (const Choice& c : {Choice{"WCSPH", FluidSolver::kWcsph, 0.0}, Choice{"DFSPH 1 %", FluidSolver::kDfsph, 0.01},
                            Choice{"DFSPH 0.1 %", FluidSolver::kDfsph, 0.001}}) {
      auto set = [&](SceneSpec s) {
        s.params.solver = c.solver;
        if (c.solver == FluidSolver::kDfsph) s.params.max_density_error = c.tolerance;
        return s;
      };
      double surge = 0, tank = 0;
      StudyRow front = damBreak("solver", c.name, set(damBase), tMax, &surge);
      SceneSpec t = presetSpec("hydrostatic");
      t.params.spacing = o.quick ? 0.04 : 0.02;
      StudyRow pressure = hydrostatic("solver", c.name, set(t), settle, average, &tank);
      StudyRow squeezedFront = front, squeezedTank = pressure;
      squeezedFront.reference = "mean compression (dam break)", squeezedFront.error = surge;
      squeezedTank.reference = "mean compression (tank)", squeezedTank.error = tank;
      for (StudyRow r : {front, squeezedFront, pressure, squeezedTank}) add(std::move(r));
    }
  }

  markPareto(rows);
  return rows;
}

void markPareto(std::vector<StudyRow>& rows) {
  for (StudyRow& r : rows) {
    r.pareto = r.status == "ok" && std::isfinite(r.error);
    if (!r.pareto) continue;
    for (const StudyRow& q : rows) {
      if (&q == &r || q.study != r.study || q.reference != r.reference || q.status != "ok") continue;
      const bool noWorse = q.cost <= r.cost && q.error <= r.error;
      const bool better = q.cost < r.cost || q.error < r.error;
      if (noWorse && better) r.pareto = false;
    }
  }
}

std::string studyCsv(const std::vector<StudyRow>& rows) {
  auto quote = [](const std::string& s) {
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  std::ostringstream o;
  o << "study,reference,choice,error,wall_s,simulated_s,cost_s_per_unit,particles,pareto,status\n";
  o << std::setprecision(9);
  for (const StudyRow& r : rows)
    o << r.study << "," << quote(r.reference) << "," << quote(r.choice) << "," << r.error << ","
      << r.wall_seconds << "," << r.simulated_seconds << "," << r.cost << "," << r.particles
      << "," << (r.pareto ? 1 : 0) << "," << quote(r.status) << "\n";
  return o.str();
}

std::string studyMarkdown(const std::vector<StudyRow>& rows) {
  std::ostringstream o;
  std::vector<std::string> groups;
  for (const StudyRow& r : rows)
    if (std::find(groups.begin(), groups.end(), r.study + " — " + r.reference) == groups.end())
      groups.push_back(r.study + " — " + r.reference);
  for (const std::string& g : groups) {
    bool first = true;
    for (const StudyRow& r : rows) {
      if (r.study + " — " + r.reference != g) continue;
      const bool frame = r.simulated_seconds == 0;
      if (first) {
        first = false;
        o << "\n### " << g << "\n\n| choice | error | wall s | "
          << (frame ? "ms per frame" : "wall s per simulated s") << " | particles | Pareto |\n"
          << "|---|---:|---:|---:|---:|:-:|\n";
      }
      o << "| " << r.choice << " | " << fmt(r.error) << " | " << fmt(r.wall_seconds, 3) << " | "
        << fmt(frame ? r.cost * 1000 : r.cost, 3) << " | " << r.particles << " | "
        << (r.pareto ? "●" : "") << " |";
      if (r.status != "ok") o << " " << r.status.substr(0, 120);
      o << "\n";
    }
  }
  return o.str();
}

std::string studySvg(const std::vector<StudyRow>& rows, const std::string& study,
                     const std::string& reference) {
  std::vector<const StudyRow*> pts;
  for (const StudyRow& r : rows)
    if (r.study == study && r.reference == reference && std::isfinite(r.error) &&
        std::isfinite(r.cost) && r.cost > 0)
      pts.push_back(&r);
  const double W = 560, H = 360, L = 70, R = 20, T = 30, B = 50;
  double cmin = 1e300, cmax = -1e300, emin = 1e300, emax = -1e300;
  const double floorErr = 1e-16;
  for (const StudyRow* p : pts) {
    cmin = std::min(cmin, p->cost), cmax = std::max(cmax, p->cost);
    const double e = std::max(p->error, floorErr);
    emin = std::min(emin, e), emax = std::max(emax, e);
  }
  if (pts.empty()) cmin = emin = 1, cmax = emax = 10;
  // Whole decades around the data.
  const double c0 = std::floor(std::log10(cmin)), c1 = std::max(std::ceil(std::log10(cmax)), c0 + 1);
  const double e0 = std::floor(std::log10(emin)), e1 = std::max(std::ceil(std::log10(emax)), e0 + 1);
  auto X = [&](double c) { return L + (std::log10(c) - c0) / (c1 - c0) * (W - L - R); };
  auto Y = [&](double e) {
    return H - B - (std::log10(std::max(e, floorErr)) - e0) / (e1 - e0) * (H - T - B);
  };
  const bool frame = !pts.empty() && pts.front()->simulated_seconds == 0;
  std::ostringstream o;
  o << std::setprecision(5);
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << L << "\" y=\"18\" font-size=\"13\">" << study << ": " << reference
    << " error against cost</text>\n";
  for (double d = c0; d <= c1; ++d)
    o << "<line x1=\"" << X(std::pow(10, d)) << "\" y1=\"" << T << "\" x2=\"" << X(std::pow(10, d))
      << "\" y2=\"" << H - B << "\" stroke=\"#ddd\"/><text x=\"" << X(std::pow(10, d))
      << "\" y=\"" << H - B + 14 << "\" text-anchor=\"middle\">1e" << d << "</text>\n";
  for (double d = e0; d <= e1; ++d)
    o << "<line x1=\"" << L << "\" y1=\"" << Y(std::pow(10, d)) << "\" x2=\"" << W - R
      << "\" y2=\"" << Y(std::pow(10, d)) << "\" stroke=\"#ddd\"/><text x=\"" << L - 6
      << "\" y=\"" << Y(std::pow(10, d)) + 4 << "\" text-anchor=\"end\">1e" << d << "</text>\n";
  o << "<text x=\"" << (L + W - R) / 2 << "\" y=\"" << H - 12 << "\" text-anchor=\"middle\">"
    << (frame ? "seconds per frame" : "wall seconds per simulated second") << "</text>\n"
    << "<text x=\"16\" y=\"" << (T + H - B) / 2 << "\" transform=\"rotate(-90 16 "
    << (T + H - B) / 2 << ")\" text-anchor=\"middle\">relative error</text>\n";
  std::vector<const StudyRow*> front;
  for (const StudyRow* p : pts)
    if (p->pareto) front.push_back(p);
  std::sort(front.begin(), front.end(), [](auto a, auto b) { return a->cost < b->cost; });
  if (front.size() > 1) {
    o << "<polyline fill=\"none\" stroke=\"#c33\" stroke-width=\"1.5\" points=\"";
    for (const StudyRow* p : front) o << X(p->cost) << "," << Y(p->error) << " ";
    o << "\"/>\n";
  }
  for (const StudyRow* p : pts)
    o << "<circle cx=\"" << X(p->cost) << "\" cy=\"" << Y(p->error) << "\" r=\"4\" fill=\""
      << (p->pareto ? "#c33" : "white") << "\" stroke=\"#c33\"/><text x=\"" << X(p->cost) + 6
      << "\" y=\"" << Y(p->error) - 6 << "\">" << p->choice << "</text>\n";
  o << "</svg>\n";
  return o.str();
}

std::string checkStudy(const std::vector<StudyRow>& rows, const std::vector<std::string>& studies) {
  for (const std::string& s : studies) {
    size_t n = 0;
    for (const StudyRow& r : rows) n += r.study == s;
    if (n < 2) return "study '" + s + "' has " + std::to_string(n) + " rows (at least 2 expected)";
  }
  for (const StudyRow& r : rows) {
    const std::string what = r.study + " / " + r.reference + " / " + r.choice;
    if (r.status != "ok") continue;  // an unstable run is a finding, reported with its reason
    if (!std::isfinite(r.error) || r.error < 0) return what + ": error is not a finite number";
    if (!(r.wall_seconds > 0) || !std::isfinite(r.cost)) return what + ": no time recorded";
  }
  return "";
}

}  // namespace scour
