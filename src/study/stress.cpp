#include "study/stress.h"
#include "engine/sources.h"
#include "engine/step_driver.h"
#include "scene/builtin_scenes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace scour {

namespace {

// "i (id k) at (x, y, z), h above the terrain, moving at (vx, vy, vz), ρ, p".
std::string fastest(const World& w) {
  const Fluid& f = w.fluid();
  size_t best = 0;
  for (size_t i = 1; i < f.size(); ++i)
    if (f.v[i].squaredNorm() > f.v[best].squaredNorm()) best = i;
  if (f.size() == 0) return "(none)";
  const Vec3f &x = f.x[best], &v = f.v[best];
  std::ostringstream o;
  o << best << " (id " << f.id[best] << ") at (" << x.x() << ", " << x.y() << ", " << x.z()
    << "), " << x.y() - w.terrain().heightAt(x.x(), x.z()) << " m above the terrain, velocity ("
    << v.x() << ", " << v.y() << ", " << v.z() << ") m/s, density " << f.rho[best]
    << " kg/m³, pressure " << f.p[best] << " Pa";
  return o.str();
}

}  // namespace

const std::vector<std::string>& stressSceneNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const BuiltinScene& b : builtinScenes())
      if (b.stress) n.push_back(b.spec.name.substr(7));  // "stress-cliffs": "cliffs"
    return n;
  }();
  return names;
}

StressScene stressSceneFrom(const SceneSpec& spec, const std::string& name) {
  StressScene s;
  s.name = name;
  s.description = spec.description;
  s.spec = spec;
  return s;
}

StressScene stressScene(const std::string& name) {
  const BuiltinScene* b = findBuiltinScene("stress-" + name);
  if (!b || !b->stress) {
    std::string valid;
    for (const std::string& n : stressSceneNames()) valid += (valid.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown stress scene '" + name + "' (valid: " + valid + ")");
  }
  return stressSceneFrom(b->spec, name);
}

std::vector<StressScene> paperStressScenes(long steps) {
  std::vector<StressScene> out;
  for (const char* name : {"canyon", "lake", "waterfall"}) {
    StressScene s;
    s.name = std::string("paper-") + name;
    s.spec = presetSpec(name);
    s.description = "the paper's " + std::string(name) + " at full size, " + std::to_string(steps) + " steps";
    s.spec.stress.duration = 1e9;
    s.max_steps = steps;
    out.push_back(std::move(s));
  }
  return out;
}

StressResult runStress(const StressScene& scene, const StressLimits& limits,
                       const std::function<void(const StressResult&)>& progress,
                       std::ostream* trace) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  StressResult r;
  r.name = scene.name;
  const Scene built = buildScene(scene.spec);
  SimParams p = built.desc.params;
  p.max_penetration_over_ds = limits.penetration_over_ds;
  WorldDesc desc = built.desc;
  desc.params = p;
  // Elastic energy of the initial pressure, Σ m p² / (2 ρ0² c²) (linearised equation of state).
  double elastic = 0;
  const double m = p.particleMass(), rc = p.rest_density * p.sound_speed;
  for (float pr : desc.pressure) elastic += m * double(pr) * double(pr) / (2 * rc * rc);
  World world(std::move(desc));
  r.particles_start = r.particles_max = r.particles_end = world.fluid().size();
  r.c_limit = p.c_max;
  r.min_dt = std::numeric_limits<double>::infinity();
  const std::vector<ParamJump>& jumps = scene.spec.stress.jumps;
  std::vector<bool> jumped(jumps.size(), false);
  if (trace)
    *trace << "step,t_s,dt_s,particles,kinetic_J,potential_J,ledger_J,elastic0_J,max_speed_m_s,"
              "penetration_ds,rho_min,rho_max,a_max,fastest\n";
  auto fail = [&](const std::string& what) {
    if (r.pass) r.pass = false, r.failure = what;
  };
  // Before each step: is there more to run, and which parameter jumps are due.
  auto more = [&] {
    if (!(world.time() < scene.spec.stress.duration && r.pass &&
          (scene.max_steps <= 0 || r.steps < scene.max_steps)))
      return false;
    for (size_t j = 0; j < jumps.size(); ++j) {
      if (jumped[j] || world.time() < jumps[j].time) continue;
      jumped[j] = true;
      SimParams q = world.params();
      const ParamInfo* info = findParam(jumps[j].key);
      if (!info || !info->dmember) throw std::logic_error("stress: bad jump " + jumps[j].key);
      q.*(info->dmember) *= jumps[j].factor;
      world.setParams(q);
    }
    return true;
  };
  // After each step, and after the one that failed: the checks the engine does not make.
  auto check = [&] {
    ++r.steps;
    const InvariantReport& inv = world.invariants();
    r.nan = inv.nan;
    r.penetration_over_ds = inv.max_penetration_over_ds;
    r.c_min = inv.c_min;
    r.c_max = inv.c_max;
    r.soil_relative = inv.soil_relative_error;
    const size_t n = world.fluid().size();
    r.particles_end = n;
    r.particles_max = std::max(r.particles_max, n);
    r.emitted = world.emitted() + world.painted();
    r.removed = world.removedBySinks() + world.removedByOutflow();
    const long expected = long(r.particles_start) + r.emitted - r.removed;
    r.lost = std::max(r.lost, std::abs(expected - long(n)));
    if (r.pass && expected != long(n)) {
      std::ostringstream o;
      o << "step " << world.steps() << ": " << n << " particles, expected " << expected
        << " (start " << r.particles_start << " + emitted " << r.emitted << " − removed "
        << r.removed << ")";
      fail(o.str());
    }
    if (r.pass || r.nan == 0) {
      // Energy at hand, counted from the lowest terrain point.
      const double floor = world.terrain().minHeight();
      const double ledger = world.energyLedger() + elastic;
      const double atHand = ledger - m * world.params().gravity * floor * double(n);
      const double mech = world.mechanicalEnergy();
      const double excess = (mech - ledger) / std::max(atHand, 1e-30);
      if (trace) {
        double kinetic = 0;
        for (const Vec3f& v : world.fluid().v) kinetic += 0.5 * m * double(v.squaredNorm());
        *trace << world.steps() << "," << world.time() << "," << world.lastDt() << "," << n << ","
               << kinetic << "," << mech - kinetic << "," << world.energyLedger() << ","
               << elastic << "," << r.max_speed << "," << r.penetration_over_ds;
        const Fluid& f = world.fluid();
        float rlo = n ? f.rho[0] : 0.0f, rhi = rlo, amax = 0;
        for (size_t i = 0; i < n; ++i)
          rlo = std::min(rlo, f.rho[i]), rhi = std::max(rhi, f.rho[i]), amax = std::max(amax, f.a[i].norm());
        *trace << "," << rlo << "," << rhi << "," << amax << ",\"" << fastest(world) << "\"\n";
      }
      r.energy_excess = std::isfinite(excess) ? std::max(r.energy_excess, excess)
                                              : std::numeric_limits<double>::infinity();
      if (r.pass && !(excess <= limits.energy_excess)) {
        std::ostringstream o;
        o << "step " << world.steps() << " (t = " << world.time()
          << " s): mechanical energy exceeds what the sources and gravity supplied by "
          << excess * 100 << " % of the energy at hand (limit " << limits.energy_excess * 100
          << " %); the fastest particle " << fastest(world);
        fail(o.str());
      }
    }
    r.simulated = world.time();
    r.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (progress && r.steps % 500 == 0) progress(r);
  };
  const RunEnd end = runWhile(world, more, [&](const StepRecord& st) {
    r.min_dt = std::min(r.min_dt, st.stats.dt);
    r.max_speed = std::max(r.max_speed, st.stats.max_speed);
    check();
  });
  if (!end.ok()) fail(end.message), check();
  if (!std::isfinite(r.min_dt)) r.min_dt = 0;
  r.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return r;
}

namespace {
std::string num(double v, int precision = 3) {
  std::ostringstream o;
  o << std::setprecision(precision) << v;
  return o.str();
}
}  // namespace

std::string stressTable(const std::vector<StressResult>& results, const StressLimits& limits) {
  std::ostringstream o;
  o << "| scene | steps | simulated s | wall s | particles (max) | NaN | depth Δs (≤ "
    << num(limits.penetration_over_ds) << ") | lost | C min | C max (≤ Cmax) | soil error (≤ "
    << num(limits.soil_relative) << ") | energy excess (≤ " << num(limits.energy_excess)
    << ") | result |\n";
  o << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for (const StressResult& r : results) {
    o << "| " << r.name << " | " << r.steps << " | " << num(r.simulated) << " | "
      << num(r.wall_seconds, 2) << " | " << r.particles_max << " | " << r.nan << " | "
      << num(r.penetration_over_ds) << " | " << r.lost << " | " << num(r.c_min) << " | "
      << num(r.c_max) << " (" << num(r.c_limit) << ") | " << num(r.soil_relative, 2) << " | "
      << num(r.energy_excess, 2) << " | " << (r.pass ? "PASS" : "FAIL") << " |\n";
  }
  return o.str();
}

std::string stressCsv(const std::vector<StressResult>& results) {
  std::ostringstream o;
  o << "scene,steps,simulated_s,wall_s,particles_start,particles_max,particles_end,emitted,"
       "removed,min_dt_s,max_speed_m_s,nan,penetration_ds,lost,c_min,c_max,c_limit,"
       "soil_relative_error,energy_excess,result\n";
  o << std::setprecision(9);
  for (const StressResult& r : results)
    o << r.name << "," << r.steps << "," << r.simulated << "," << r.wall_seconds << ","
      << r.particles_start << "," << r.particles_max << "," << r.particles_end << ","
      << r.emitted << "," << r.removed << "," << r.min_dt << "," << r.max_speed << "," << r.nan
      << "," << r.penetration_over_ds << "," << r.lost << "," << r.c_min << "," << r.c_max
      << "," << r.c_limit << "," << r.soil_relative << "," << r.energy_excess << ","
      << (r.pass ? "PASS" : "FAIL") << "\n";
  return o.str();
}

}  // namespace scour
