#include "study/stress.h"
#include "engine/sources.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace scour {

namespace {

StressScene named(const std::string& name, const std::string& description, double duration) {
  StressScene s;
  s.name = name;
  s.description = description;
  s.duration = duration;
  s.spec.name = "stress-" + name;
  s.spec.description = description;
  return s;
}

void allErosion(SceneSpec& s) {
  s.effects.erosion = s.effects.settling = s.effects.diffusion = s.effects.deposition = true;
  s.effects.no_slip = true;
  s.params.boundary_friction = 1e-4;
  s.params.diffusion = 0.01;
}

Source source(Eigen::Vector3d centre, double radius, Eigen::Vector3d direction, double rate) {
  Source src;
  src.center = centre;
  src.radius = radius;
  src.direction = direction;
  src.rate = rate;
  return src;
}

// A jet leaves a ledge 1 m above a flat rock floor and hits it at about 4.6 m/s.
StressScene waterfallDrop() {
  StressScene s = named("waterfall-drop", "a jet falling 1 m onto a flat rock floor", 0.8);
  SceneSpec& sp = s.spec;
  sp.params.spacing = 0.02;
  sp.params.sound_speed = 50.0;  // ≥ 10 × the impact speed
  allErosion(sp);
  sp.params.tau_c = 20.0;  // rock: only the impact erodes
  sp.terrain = flatTerrain(0.8, 0.4, 0.02);
  sp.sources.push_back(source({0.08, 1.0, 0.2}, 0.04, {1, 0, 0}, 0.008));
  return s;
}

// Martin & Moyce's column released in a tank only 2.5 columns long: the surge hits the far wall
// at full speed and climbs it.
StressScene dambreakWall() {
  StressScene s = named("dambreak-wall", "a dam break slamming into the tank's far wall", 1.0);
  const double a = 0.1;
  damBreakTank(s.spec, a, a / 14, 2.5 * a);
  s.spec.params.sound_speed = 25.0;
  return s;
}

// A narrow column 1.5 m deep: 15 kPa at the bottom, held at rest.
StressScene deepColumn() {
  StressScene s = named("deep-column", "a 1.5 m deep, 0.15 m wide column at rest (15 kPa)", 1.0);
  SceneSpec& sp = s.spec;
  const double H = 1.5;
  sp.params.spacing = 0.025;
  sp.params.sound_speed = 10.0 * std::sqrt(2.0 * 9.81 * H);
  sp.params.viscosity = 5e-3;
  sp.terrain = flatTerrain(0.15, 0.15, 0.05);
  sp.blocks.push_back({{0, 0, 0}, {0.15, H, 0.15}});
  return s;
}

// A fast jet (about 4 m/s) shot down a narrow, steep-sided gorge that erodes.
StressScene gorgeJet() {
  StressScene s = named("gorge-jet", "a 4 m/s jet down a narrow eroding gorge", 0.6);
  SceneSpec& sp = s.spec;
  sp.params.spacing = 0.02;
  sp.params.sound_speed = 60.0;
  allErosion(sp);
  TerrainSpec& t = sp.terrain;
  t.kind = "valley";
  t.length_x = 1.5, t.length_z = 0.3, t.cell = 0.02;
  t.slope = 0.2;
  t.side_rise = 0.4;
  const double top = t.slope * t.length_x;
  sp.sources.push_back(source({0.06, top + 0.08, 0.15}, 0.03, {1, -0.1, 0}, 0.011));
  sp.sinks.push_back({{1.35, -1.0, -1.0}, {2.0, 2.0, 2.0}});
  return s;
}

// Erosion so strong (Kε = 1000, τc = 0) that the water takes up soil until C reaches Cmax.
StressScene saturation() {
  StressScene s = named("saturation", "Kε = 1000, τc = 0: C driven to Cmax", 0.6);
  SceneSpec& sp = s.spec;
  sp.params.spacing = 0.02;
  sp.params.sound_speed = 25.0;
  allErosion(sp);
  sp.params.k_eps = 1000.0;
  sp.params.tau_c = 0.0;
  TerrainSpec& t = sp.terrain;
  t.kind = "slope";
  t.length_x = 0.8, t.length_z = 0.3, t.cell = 0.02;
  t.slope = 0.3;
  const double top = t.slope * t.length_x;
  sp.blocks.push_back({{0.0, top - 0.1, 0.0}, {0.2, top + 0.1, 0.3}, true});
  return s;
}

// An extreme Kε under a falling jet: a pit deeper than the particle spacing every few steps.
StressScene deepPits() {
  StressScene s = named("deep-pits", "Kε = 10⁴ under a falling jet digs a pit", 0.6);
  SceneSpec& sp = s.spec;
  sp.params.spacing = 0.02;
  sp.params.sound_speed = 30.0;
  allErosion(sp);
  sp.params.k_eps = 1e4;
  sp.params.tau_c = 0.0;
  sp.terrain = flatTerrain(0.5, 0.5, 0.02);
  sp.terrain.base = 0.3;  // soil to dig into above the zero the budget counts from
  sp.sources.push_back(source({0.25, 0.6, 0.25}, 0.04, {0, -1, 0}, 0.004));
  return s;
}

// Three shelves, each 0.3 m above the next, joined by near-vertical risers (over 2 % of a step).
StressScene cliffs() {
  StressScene s = named("cliffs", "water pouring over near-vertical 0.3 m cliffs", 0.8);
  SceneSpec& sp = s.spec;
  sp.params.spacing = 0.02;
  sp.params.sound_speed = 40.0;
  allErosion(sp);
  TerrainSpec& t = sp.terrain;
  t.kind = "terraces";
  t.length_x = 0.9, t.length_z = 0.3, t.cell = 0.015;
  t.slope = 1.0;
  t.levels = 3;
  t.riser = 0.02;
  const double top = t.slope * t.length_x;
  sp.blocks.push_back({{0.0, top - 0.3, 0.0}, {0.22, top + 0.12, 0.3}, true});
  return s;
}

// A source whose disk reaches past the corner of the domain, aimed into the walls.
StressScene edgeSource() {
  StressScene s = named("edge-source", "a source in the domain's corner, aimed at the walls", 0.8);
  SceneSpec& sp = s.spec;
  sp.params.spacing = 0.02;
  sp.params.sound_speed = 30.0;
  allErosion(sp);
  sp.terrain = flatTerrain(0.4, 0.4, 0.02);
  sp.sources.push_back(source({0.03, 0.2, 0.03}, 0.04, {-1, -0.5, -1}, 0.006));
  return s;
}

// The default river at a fifth of its particles; at 0.3 s Kε jumps ×100 and D ×10.
StressScene parameterJump() {
  StressScene s = named("parameter-jump", "the default river; at 0.3 s Kε ×100 and D ×10", 0.7);
  s.spec = presetSpec("default", 0.2);
  s.jumps.push_back({0.3, "erosion.k_eps", 100.0});
  s.jumps.push_back({0.3, "sediment.diffusion", 10.0});
  return s;
}

// A dam break stepped at the largest CFL and force factors the parameter table accepts, with no
// upper bound on Δt but theirs. (At λ = 0.5 with λ_f = 0.25 this scene gains 7 % energy, at
// λ = 1, λ_f = 1 it gains 6 % within 50 steps: the table's limits are these.)
StressScene cflLimit() {
  StressScene s = named("cfl-limit", "a dam break at the largest CFL and force factors", 0.8);
  const double a = 0.1;
  damBreakTank(s.spec, a, a / 12, 4 * a);
  SimParams& p = s.spec.params;
  p.sound_speed = 20.0;
  p.max_dt = 0.01;
  p.cfl = findParam("time.cfl")->max;
  p.force_cfl = findParam("time.force_cfl")->max;
  return s;
}

// A cloudburst far beyond nature on a crater, eroding its sides.
StressScene cloudburst() {
  StressScene s = named("cloudburst", "100 m/h of rain eroding a crater", 0.8);
  SceneSpec& sp = s.spec;
  sp.params.spacing = 0.02;
  sp.params.sound_speed = 30.0;
  allErosion(sp);
  sp.params.tau_c = 0.5;
  TerrainSpec& t = sp.terrain;
  t.kind = "bowl";
  t.length_x = t.length_z = 0.6;
  t.cell = 0.02;
  t.side_rise = 0.25;
  Rain r;
  r.lo_x = r.lo_z = 0.0;
  r.hi_x = r.hi_z = 0.6;
  r.intensity_mm_h = 1.0e5;  // 100 m/h: about 1,300 drops a second on the crater
  r.drop_height = 0.15;
  sp.rain.push_back(r);
  return s;
}

// Water leaving over the open edges of a sloping plain, carrying sediment out.
StressScene openOutflow() {
  StressScene s = named("open-outflow", "a river leaving through the open domain edge", 0.8);
  SceneSpec& sp = s.spec;
  sp.params.spacing = 0.02;
  sp.params.sound_speed = 30.0;
  allErosion(sp);
  sp.params.tau_c = 0.5;
  sp.domain.walls = false;
  TerrainSpec& t = sp.terrain;
  t.kind = "valley";
  t.length_x = 0.8, t.length_z = 0.4, t.cell = 0.02;
  t.slope = 0.4;
  t.side_rise = 0.1;
  const double top = t.slope * t.length_x;
  sp.sources.push_back(source({0.06, top + 0.12, 0.2}, 0.04, {1, -0.5, 0}, 0.004));
  return s;
}

// The default river with grains lighter than water (ρs = 300 kg/m³): what the water erodes
// rises to its surface instead of settling, and the budget must still close.
StressScene lightSediment() {
  StressScene s = named("light-sediment", "the default river eroding grains lighter than water", 0.6);
  s.spec = presetSpec("default", 0.2);
  s.spec.name = "stress-light-sediment";
  s.spec.params.sediment_density = 300.0;
  s.spec.params.k_eps = 10.0;
  // A loaded particle at the bottom of the water from the start: before rising grains were
  // handled, its negative settling flux broke the soil budget in the first step.
  const WaterBlock& b = s.spec.blocks.front();
  s.spec.sediment.push_back({{0.5 * (b.min.x() + b.max.x()), b.min.y(), 0.5 * (b.min.z() + b.max.z())}, 0.3});
  return s;
}

// The settling lattice (paper Fig. 4) with grains lighter than water, loaded at the top: before
// rising grains were handled, the soil budget was off by 3e-5 in the first step.
StressScene floatingGrains() {
  StressScene s = named("floating-grains", "the settling lattice with grains of 500 kg/m³", 1.0);
  s.spec = presetSpec("settling");
  s.spec.name = "stress-floating-grains";
  s.spec.params.sediment_density = 500.0;
  s.spec.params.grain_radius = 1e-4;
  return s;
}

// Grains barely heavier than water (ρs − ρ0 = 10⁻³ kg/m³): a settling speed of nanometres a second.
StressScene neutralSediment() {
  StressScene s = named("neutral-sediment", "grains 1 g/m³ heavier than water, under a jet", 0.6);
  s.spec = presetSpec("default", 0.2);
  s.spec.name = "stress-neutral-sediment";
  s.spec.params.sediment_density = s.spec.params.rest_density + 1e-3;
  s.spec.params.k_eps = 10.0;
  return s;
}

// Coarse, heavy grains (1 mm, 8000 kg/m³) torn from the bed by a jet and dumped at once: the
// deposit grows under the water as fast as the grains fall.
StressScene sedimentDump() {
  StressScene s = named("sediment-dump", "a jet loading coarse heavy grains that settle at once", 0.6);
  SceneSpec& sp = s.spec;
  sp.params.spacing = 0.02;
  sp.params.sound_speed = 40.0;
  allErosion(sp);
  sp.params.k_eps = 100.0;
  sp.params.tau_c = 0.0;
  sp.params.grain_radius = 1e-3;
  sp.params.sediment_density = 8000.0;
  sp.terrain = flatTerrain(0.5, 0.3, 0.02);
  sp.terrain.base = 0.2;
  sp.sources.push_back(source({0.1, 0.45, 0.15}, 0.04, {1, -1, 0}, 0.006));
  return s;
}

// Rain on a rectangle ten times the terrain's size: only the terrain's share falls, at the
// rain's intensity (docs/scene-format.md).
StressScene rainOverhang() {
  StressScene s = named("rain-overhang", "rain on a rectangle 10× the terrain, clipped to it", 0.8);
  SceneSpec& sp = s.spec;
  sp.params.spacing = 0.02;
  sp.params.sound_speed = 30.0;
  allErosion(sp);
  sp.params.tau_c = 0.5;
  sp.terrain.kind = "rolling";
  sp.terrain.length_x = sp.terrain.length_z = 0.5;
  sp.terrain.cell = 0.02;
  sp.terrain.amplitude = 0.05;
  sp.terrain.base = 0.1;
  Rain r;
  r.lo_x = r.lo_z = -2.25;
  r.hi_x = r.hi_z = 2.75;
  r.intensity_mm_h = 5.0e4;
  sp.rain.push_back(r);
  return s;
}

// A source disk a hundredth of Δs wide at the largest rate its one slot allows: an exit speed
// just under the sound speed.
StressScene needleSource() {
  StressScene s = named("needle-source", "a disk Δs/100 wide jetting at 0.9 of the sound speed", 0.4);
  SceneSpec& sp = s.spec;
  sp.params.spacing = 0.02;
  sp.params.sound_speed = 20.0;
  allErosion(sp);
  sp.terrain = flatTerrain(1.0, 0.4, 0.02);
  sp.terrain.base = 0.2;
  const double rate = 0.9 * sp.params.sound_speed * sp.params.spacing * sp.params.spacing;
  sp.sources.push_back(source({0.05, 0.4, 0.2}, 2e-4, {1, -0.2, 0}, rate));
  return s;
}

// A jet of `speed` shot down from 0.4 m above the floor of a closed 0.5 m box, at sound speed
// `soundSpeed`: the splash crowds the corners.
StressScene fastJet(const std::string& name, const std::string& what, double speed,
                    double soundSpeed, double duration) {
  StressScene s = named(name, what, duration);
  SceneSpec& sp = s.spec;
  sp.params.spacing = 0.02;
  sp.params.sound_speed = soundSpeed;
  // Every erosion effect at its default strength, as a user's first scene file has them.
  Effects& fx = sp.effects;
  fx.erosion = fx.settling = fx.diffusion = fx.deposition = fx.no_slip = true;
  sp.terrain = flatTerrain(0.5, 0.5, 0.01);
  sp.terrain.base = 0.3;
  // The exit speed is rate / (slots · Δs²).
  const double radius = 0.03, ds = sp.params.spacing;
  const double rate = speed * double(diskLattice(radius, ds).size()) * ds * ds;
  sp.sources.push_back(source({0.25, 0.7, 0.25}, radius, {0.3, -1, 0.1}, rate));
  return s;
}

// Before the δ-SPH term was regularised (η² = 0.01 h²) a splash particle driven into a
// compressed one near a corner took it to 2.9 ρ0 in one step; this scene gained 6.2 % of the
// energy at hand by 0.375 s.
StressScene fastJetFloor() {
  return fastJet("fast-jet-floor", "an 8 m/s jet onto the floor of a closed 0.5 m box", 8.0, 80.0,
                 0.6);
}

// Needles 8 cm high and 2 cm (Δs) apart on a grid of Δs/2. Before the walls saw the terrain
// through its Δs/2 envelope, the plane under a particle turned with every cell and the first
// impact gained 8.8 % energy in 0.056 s; before the CFL step followed the compressed sound speed,
// a 10 m/s jet put a particle 0.55 Δs below the terrain. The sound speed is 10 × the impact
// speed, the weakly compressible rule. Faster than that rule allows (10 m/s at c_s = 80 or 104 m/s) a
// squeezed particle is still shot off at 50 m/s and can reach 0.5 Δs below the terrain
// (docs/stress.md).
StressScene jetOnSpikes() {
  const double v = 8.0, impact = std::sqrt(v * v + 2.0 * SimParams{}.gravity * 0.4);
  StressScene s = fastJet("jet-on-spikes", "an 8 m/s jet onto fBm needles finer than Δs", v,
                          10.0 * impact, 0.6);
  s.spec.terrain.kind = "fbm";
  s.spec.terrain.noise.amplitude = 0.08;
  s.spec.terrain.noise.feature = 0.02;
  return s;
}

using Maker = StressScene (*)();
struct Entry {
  const char* name;
  Maker make;
};
const std::vector<Entry>& entries() {
  static const std::vector<Entry> e{
      {"waterfall-drop", waterfallDrop}, {"dambreak-wall", dambreakWall},
      {"deep-column", deepColumn},       {"gorge-jet", gorgeJet},
      {"saturation", saturation},        {"deep-pits", deepPits},
      {"cliffs", cliffs},                {"edge-source", edgeSource},
      {"parameter-jump", parameterJump}, {"cfl-limit", cflLimit},
      {"cloudburst", cloudburst},        {"open-outflow", openOutflow},
      {"light-sediment", lightSediment}, {"neutral-sediment", neutralSediment},
      {"floating-grains", floatingGrains}, {"sediment-dump", sedimentDump},
      {"rain-overhang", rainOverhang},   {"needle-source", needleSource},
      {"fast-jet-floor", fastJetFloor},  {"jet-on-spikes", jetOnSpikes},
  };
  return e;
}

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
    for (const Entry& e : entries()) n.push_back(e.name);
    return n;
  }();
  return names;
}

StressScene stressScene(const std::string& name) {
  for (const Entry& e : entries())
    if (name == e.name) return e.make();
  std::string valid;
  for (const Entry& e : entries()) valid += (valid.empty() ? "" : ", ") + std::string(e.name);
  throw std::invalid_argument("unknown stress scene '" + name + "' (valid: " + valid + ")");
}

std::vector<StressScene> paperStressScenes(long steps) {
  std::vector<StressScene> out;
  for (const char* name : {"canyon", "lake", "waterfall"}) {
    StressScene s;
    s.name = std::string("paper-") + name;
    s.spec = presetSpec(name);
    s.description = "the paper's " + std::string(name) + " at full size, " + std::to_string(steps) + " steps";
    s.duration = 1e9;
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
  std::vector<bool> jumped(scene.jumps.size(), false);
  if (trace)
    *trace << "step,t_s,dt_s,particles,kinetic_J,potential_J,ledger_J,elastic0_J,max_speed_m_s,"
              "penetration_ds,rho_min,rho_max,a_max,fastest\n";
  auto fail = [&](const std::string& what) {
    if (r.pass) r.pass = false, r.failure = what;
  };
  while (world.time() < scene.duration && r.pass && (scene.max_steps <= 0 || r.steps < scene.max_steps)) {
    for (size_t j = 0; j < scene.jumps.size(); ++j) {
      if (jumped[j] || world.time() < scene.jumps[j].time) continue;
      jumped[j] = true;
      SimParams q = world.params();
      const ParamInfo* info = findParam(scene.jumps[j].key);
      if (!info || !info->dmember) throw std::logic_error("stress: bad jump " + scene.jumps[j].key);
      q.*(info->dmember) *= scene.jumps[j].factor;
      world.setParams(q);
    }
    try {
      const StepStats st = world.step();
      r.min_dt = std::min(r.min_dt, st.dt);
      r.max_speed = std::max(r.max_speed, st.max_speed);
    } catch (const InvariantViolation& e) {
      fail(e.what());
    }
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
  }
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
