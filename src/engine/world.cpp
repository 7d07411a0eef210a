#include "engine/world.h"

#include "engine/limits.h"
#include "engine/parallel.h"
#include "engine/world_parts.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <istream>
#include <ostream>
#include <sstream>
#include <type_traits>

namespace scour {

using detail::makeEmitter;
using detail::require;
using detail::validateSink;
using detail::wallSurfaceFor;

const char* passName(Pass p) {
  switch (p) {
    case Pass::kNeighborSearch: return "neighbor_search";
    case Pass::kDensity: return "density";
    case Pass::kForces: return "forces";
    case Pass::kBoundaryForces: return "boundary_forces";
    case Pass::kIntegrate: return "integrate";
    case Pass::kSources: return "sources";
    case Pass::kSinks: return "sinks";
    case Pass::kRain: return "rain";
    case Pass::kBoundaryParticles: return "boundary_particles";
    case Pass::kBoundaryNeighbors: return "boundary_neighbors";
    case Pass::kNoSlip: return "no_slip";
    case Pass::kSediment: return "sediment";
    case Pass::kErosion: return "erosion";
    case Pass::kTerrain: return "terrain";
    case Pass::kFlowMaps: return "flow_maps";
    case Pass::kInvariants: return "invariants";
    case Pass::kPressureSolve: return "pressure_solve";
    case Pass::kDivergenceSolve: return "divergence_solve";
    case Pass::kCount: break;
  }
  return "?";
}

Table1Group table1Group(Pass p) {
  switch (p) {
    case Pass::kNeighborSearch:
    case Pass::kDensity:
    case Pass::kForces:
    case Pass::kBoundaryForces:
    case Pass::kIntegrate:
    case Pass::kPressureSolve:
    case Pass::kDivergenceSolve:
    case Pass::kNoSlip: return Table1Group::kSph;
    case Pass::kBoundaryParticles:
    case Pass::kBoundaryNeighbors: return Table1Group::kBoundary;
    case Pass::kSediment:
    case Pass::kErosion:
    case Pass::kTerrain:
    case Pass::kFlowMaps: return Table1Group::kErosion;
    default: return Table1Group::kOther;
  }
}

namespace {

SimParams resolve(SimParams p) {
  double contact = p.contact_over_spacing > 0 ? p.contact_over_spacing * p.spacing : p.spacing;
  // DFSPH: the walls hold the water through the solves (dfsph.h) and the hard floor catches what
  // they miss; the penalty acts only when the scene asks for it (model.md, "the implicit solver").
  if (p.solver == FluidSolver::kDfsph && p.penalty_stiffness <= 0) {
    p.penalty_stiffness = 0;
    if (p.penalty_damping <= 0) p.penalty_damping = 0;
    return p;
  }
  // K_S: a particle arriving at a tenth of the sound speed is stopped within the contact distance.
  if (p.penalty_stiffness <= 0) p.penalty_stiffness = std::pow(0.1 * p.sound_speed / contact, 2);
  if (p.penalty_damping <= 0) p.penalty_damping = 2.0 * std::sqrt(p.penalty_stiffness);
  return p;
}

// A particle below the plane of the triangle under it (along the plane's normal, as the
// invariant check measures depth) goes back onto the plane, its velocity into it removed: an
// inelastic contact. Returns whether it was below.
bool putOnFloor(const Heightfield& floor, Vec3f& x, Vec3f& v) {
  if (!x.allFinite()) return false;
  const SurfacePoint s = floor.surface(x.x(), x.z());
  const double depth = (s.height - double(x.y())) * s.normal.y();
  if (!(depth > 0)) return false;
  const Vec3f n = s.normal.cast<float>();
  x += float(depth) * n;
  const float into = v.dot(n);
  if (into < 0) v -= into * n;
  return true;
}

}  // namespace

World::World(WorldDesc d)
    : params_(resolve(d.params)),
      sph_(params_),
      dfsphK_(sph_, params_.spacing),
      sediment_(params_),
      terrain_(std::move(d.terrain)),
      domain_(d.domain),
      effects_(d.effects),
      sampler_(terrain_, params_.spacing, params_.boundary_sampling) {
  std::string bad = validateParams(d.params);
  require(bad.empty(), bad);
  if (!effects_.surface_tension) sph_.kappa = 0;  // the cohesion term is skipped inside the force pass
  require(terrain_.nx() >= 2 && terrain_.nz() >= 2, "terrain: needs at least 2 × 2 vertices");
  require(terrain_.dx() > 0 && terrain_.dz() > 0, "terrain: cell size must be positive");
  for (double h : terrain_.heights()) require(std::isfinite(h), "terrain: heights must be finite");
  initialTerrain_ = terrain_;
  factor_ = params_.morphological_factor;
  wall_ = wallSurfaceFor(terrain_, params_);
  vertexArea_ = vertexAreas(terrain_);
  terrainReference_ = terrain_.minHeight();
  accumulator_.resize(terrain_.triangleCount(), terrain_.heights().size(), terrain_.nx() - 1);
  flow_.reset(terrain_.nx(), terrain_.nz());
  require(double(terrain_.heights().size()) <= Limits::kMaxTerrainVertices, "terrain: more vertices than the limit");
  supply_.maxParticles = size_t(particleCapacity(double(terrain_.heights().size())));
  require(d.particles.size() <= supply_.maxParticles, "particles: more than the memory limit allows");
  simulationBox();
  supply_.sinks = std::move(d.sinks);
  for (size_t s = 0; s < d.sources.size(); ++s)
    supply_.emitters.push_back(makeEmitter(d.sources[s], params_, "sources[" + std::to_string(s) + "]"));
  for (size_t s = 0; s < supply_.sinks.size(); ++s) validateSink(supply_.sinks[s], "sinks[" + std::to_string(s) + "]");
  for (size_t r = 0; r < d.rain.size(); ++r) {
    const Rain& rn = d.rain[r];
    std::string at = "rain[" + std::to_string(r) + "]";
    require(std::isfinite(rn.lo_x) && std::isfinite(rn.hi_x) && std::isfinite(rn.lo_z) &&
                std::isfinite(rn.hi_z) && rn.hi_x > rn.lo_x && rn.hi_z > rn.lo_z,
            at + ".region must be a finite rectangle with max > min");
    require(rn.intensity_mm_h > 0 && std::isfinite(rn.intensity_mm_h),
            at + ".intensity_mm_h must be positive");
    require(rn.drop_height >= 0 && std::isfinite(rn.drop_height),
            at + ".drop_height must be finite and ≥ 0");
    require(std::isfinite(rn.drop_speed), at + ".drop_speed must be finite");
    require(rainArea(rn) > 0, at + ": the rectangle does not overlap the terrain");
    const std::string bad = checkRainWork(rn, rainArea(rn), params_, at);
    require(bad.empty(), bad);
    supply_.rain.push_back(RainState{rn, 0.0, 0, 0, 0});
  }
  require(d.pressure.empty() || d.pressure.size() == d.particles.size(),
          "pressure: one value per particle expected");
  for (size_t i = 0; i < d.particles.size(); ++i) {
    require(d.particles[i].allFinite(), "particles: positions must be finite");
    double p0 = d.pressure.empty() ? 0.0 : d.pressure[i];
    require(std::isfinite(p0) && p0 >= 0, "pressure: must be finite and ≥ 0");
    fluid_.push(d.particles[i], Vec3f::Zero(), supply_.nextId++, float(sph_.densityFor(p0)));
    if (implicit()) fluid_.p.back() = float(p0), fluid_.rho.back() = float(sph_.rho0);  // DFSPH's first warm start
  }
  require(d.concentration.empty() || d.concentration.size() == d.particles.size(),
          "concentration: one value per particle expected");
  for (size_t i = 0; i < d.concentration.size(); ++i) {
    const double c = d.concentration[i];
    require(std::isfinite(c) && c >= 0 && c <= params_.c_max, "concentration: must lie in [0, c_max]");
    fluid_.sed[i] = c * sediment_.volume;
  }
  ledger_.initialSoil = soilBudget().total();
  ledger_.energy = mechanicalEnergy();
  for (size_t i = 0; i < fluid_.size(); ++i) {
    const double c = fluid_.sed[i] / sediment_.volume;
    ledger_.invariants.c_min = i == 0 ? c : std::min(ledger_.invariants.c_min, c);
    ledger_.invariants.c_max = i == 0 ? c : std::max(ledger_.invariants.c_max, c);
  }
  ledger_.defects.c_min_raw = ledger_.invariants.c_min, ledger_.defects.c_max_raw = ledger_.invariants.c_max;
  searchNeighbors();
  // Frozen fluid: no SPH pass ever runs.
  if (effects_.fluid_motion) implicit() ? implicitAccelerations(false) : computeAccelerations();
}

double World::chooseDt() const {
  if (params_.fixed_dt > 0) return params_.fixed_dt;
  float v2 = 0, a2 = 0, rhoMax = 0;
  const size_t n = fluid_.size();
#pragma omp parallel for schedule(static) reduction(max : v2, a2, rhoMax) if (n >= kParallelFrom)
  for (size_t i = 0; i < n; ++i) {
    v2 = std::max(v2, fluid_.v[i].squaredNorm());
    a2 = std::max(a2, fluid_.a[i].squaredNorm());
    rhoMax = std::max(rhoMax, fluid_.rho[i]);
  }
  const double h = sph_.h;
  double dt = params_.max_dt;
  if (effects_.fluid_motion && implicit()) {
    // DFSPH: no sound to resolve. A particle moves at most λ_v h, the non-pressure forces (gravity)
    // stay resolved, viscosity stays explicitly stable; the penalty bounds Δt only if it is on.
    dt = std::min(params_.implicit_max_dt, params_.velocity_cfl * h / std::sqrt(double(v2)));
    if (a2 > 0) dt = std::min(dt, params_.force_cfl * std::sqrt(h / std::sqrt(double(a2))));
    if (params_.viscosity > 0) dt = std::min(dt, 0.125 * h * h / params_.viscosity);
    if (params_.penalty_stiffness > 0) dt = std::min(dt, 0.5 / std::sqrt(params_.penalty_stiffness));
  } else if (effects_.fluid_motion) {
    dt = std::min(dt, params_.cfl * h / std::max(sph_.soundSpeed(rhoMax), std::sqrt(double(v2))));
    if (a2 > 0) dt = std::min(dt, params_.force_cfl * std::sqrt(h / std::sqrt(double(a2))));
    if (densityRate_ > 0) dt = std::min(dt, params_.density_cfl / densityRate_);
    if (params_.viscosity > 0) dt = std::min(dt, 0.125 * h * h / params_.viscosity);
    dt = std::min(dt, 0.5 / std::sqrt(params_.penalty_stiffness));
  }
  // Explicit sediment transport: diffusion needs Δt ≤ h²/(8D) (model.md); the donor–acceptor
  // settling moves at most a fraction λ of h per step.
  // Every K-th step the exchange spans K steps: the limits hold for the span.
  const double every = double(params_.exchange_every);
  if (effects_.diffusion && params_.diffusion > 0) dt = std::min(dt, 0.125 * h * h / params_.diffusion / every);
  if ((effects_.settling || effects_.deposition) && sediment_.vs0 != 0)
    dt = std::min(dt, params_.cfl * h / std::abs(sediment_.vs0) / every);
  return dt;
}

void World::searchNeighbors() {
  timed(Pass::kNeighborSearch, [&] { buildFluidLists(); });
  if (!needsBoundary()) return;
  timed(Pass::kBoundaryParticles, [&] {
    if (sampler_.updateActiveTiles(terrain_, fluid_.x, sph_.h)) sampler_.generate(terrain_, boundary_);
  });
  timed(Pass::kBoundaryNeighbors, [&] { buildBoundaryLists(); });
}

void World::buildFluidLists() {
  neighbors_.buildFluid(fluid_.x, float(sph_.h), params_.neighbor_search);
}

void World::buildBoundaryLists() {
  neighbors_.buildBoundary(fluid_.x, boundary_.x, float(sph_.h), params_.neighbor_search);
}

void World::computeAccelerations() {
  if (vhat_.size() != fluid_.size()) vhat_ = fluid_.v;
  timed(Pass::kDensity, [&] {
    if (sph_.continuity)
      // fluid_.v holds v(t + Δt/2) here
      densityRate_ = integrateDensity(sph_, neighbors_.fluid(), wall_.of(terrain_), domain_, fluid_.v, dt_, fluid_);
    else
      // No continuity rate to bound Δt.
      computeDensity(sph_, neighbors_.fluid(), wall_.of(terrain_), domain_, fluid_), densityRate_ = 0;
  });
  timed(Pass::kForces, [&] { computeForces(sph_, neighbors_.fluid(), vhat_, fluid_); });
  timed(Pass::kBoundaryForces, [&] { applyBoundaryForces(sph_, wall_.of(terrain_), domain_, vhat_, fluid_); });
  if (effects_.no_slip) timed(Pass::kNoSlip, [&] { applyNoSlip(sph_, neighbors_.boundary(), boundary_, vhat_, fluid_); });
}

void World::implicitAccelerations(bool divergence) {
  timed(Pass::kDensity, [&] { dfsphFactors(dfsphK_, neighbors_.fluid(), wall_.of(terrain_), domain_, fluid_, dfsph_); });
  if (divergence)
    timed(Pass::kDivergenceSolve, [&] {
      divergenceSolve_ = solveDivergence(dfsphK_, neighbors_.fluid(), dt_, params_.max_divergence_error,
                                         params_.max_iterations, fluid_, dfsph_);
    });
  vhat_ = fluid_.v;  // the non-pressure forces act at the step's end velocity
  timed(Pass::kForces, [&] { computeForces(sph_, neighbors_.fluid(), vhat_, fluid_, false); });
  timed(Pass::kBoundaryForces, [&] { applyBoundaryForces(sph_, wall_.of(terrain_), domain_, vhat_, fluid_, false); });
  if (effects_.no_slip) timed(Pass::kNoSlip, [&] { applyNoSlip(sph_, neighbors_.boundary(), boundary_, vhat_, fluid_); });
}

void World::simulationBox() {
  const double pad = std::max(terrain_.xMax() - terrain_.x0(), terrain_.zMax() - terrain_.z0());
  const double climb = params_.sound_speed * params_.sound_speed / (2 * std::max(params_.gravity, 0.1));
  boxLo_ = Vec3f(float(terrain_.x0() - pad), float(terrain_.minHeight() - pad), float(terrain_.z0() - pad));
  boxHi_ = Vec3f(float(terrain_.xMax() + pad), float(terrain_.maxHeight() + pad + climb), float(terrain_.zMax() + pad));
}

void World::sedimentWork(double span) {
  SedimentEffects sfx{effects_.settling, effects_.diffusion, effects_.deposition, effects_.erosion};
  if (sfx.settling || sfx.diffusion || sfx.deposition) {
    timed(Pass::kSediment, [&] {
      transferSediment(sediment_, sfx, neighbors_.fluid(), neighbors_.boundary(), boundary_, span, fluid_, accumulator_, sedimentWork_);
      const SedimentDefects& d = sedimentWork_.defects;
      if (sediment_.advection == SettlingAdvection::kNaiveGradient && sfx.settling && fluid_.size() > 0) {
        ledger_.defects.created += d.created;
        ledger_.defects.clipped += d.clipped;
        ledger_.defects.c_min_raw = std::min(ledger_.defects.c_min_raw, d.c_min_raw);
        ledger_.defects.c_max_raw = std::max(ledger_.defects.c_max_raw, d.c_max_raw);
      }
    });
  }
  if (sfx.erosion) timed(Pass::kErosion, [&] { erode(sediment_, neighbors_.boundary(), boundary_, span, fluid_, accumulator_, sedimentWork_); });
  if (sfx.erosion || sfx.deposition) {
    timed(Pass::kTerrain, [&] {
      // The geologic clock (model.md, "two clocks"): the bed takes N times the step's exchange;
      // the guard halves N until no boundary particle's bed moves more than the bound.
      // erosion.max_bed_step is per WCSPH step, λ h / c_s of water; a DFSPH step k times as long
      // may move the bed k times as far, so that the bed's speed against the water, which the
      // guard bounds, and with it N, are the same under either solver (model.md, "the guard").
      // An exchange every K steps is K steps' worth: its bed may move K times as far.
      double bound = params_.max_bed_step * params_.spacing * double(params_.exchange_every);
      if (implicit()) bound *= std::max(1.0, dt_ / (params_.cfl * sph_.h / params_.sound_speed));
      const double peak = accumulator_.bedMotion(boundary_, INFINITY).peak;
      if (stepFactor_ > 1 && stepFactor_ * peak > bound) {
        const double was = stepFactor_;
        while (stepFactor_ > 1 && stepFactor_ * peak > bound) stepFactor_ = std::max(1.0, 0.5 * stepFactor_);
        factor_ = stepFactor_;
        Ledger::BedGuard& g = ledger_.guard;
        g.lowest = g.lowered == 0 ? stepFactor_ : std::min(g.lowest, stepFactor_);
        ++g.lowered, g.lastAt = time_, g.lastFrom = was;
      }
      const auto motion = accumulator_.bedMotion(boundary_, 0.1 * bound / stepFactor_);
      bedStep_ = stepFactor_ * motion.peak / params_.spacing;
      bedFast_ = motion.area > 0 ? motion.fastArea / motion.area : 0.0;
      accumulator_.spread(boundary_, stepFactor_, ledger_.morphological);
      const std::vector<int> moved = applyTerrainChange(terrain_, vertexArea_, accumulator_, kTerrainApplyOverSpacing * params_.spacing);
      if (!moved.empty()) BoundarySampler::follow(terrain_, accumulator_.vertexMark, accumulator_.epoch, boundary_);
      wall_.follow(terrain_, moved);
    });
  }
}

void World::setParams(const SimParams& q) {
  std::string bad = validateParams(q);
  require(bad.empty(), bad);
  require(q.spacing == params_.spacing && q.support_over_spacing == params_.support_over_spacing &&
              q.rest_density == params_.rest_density,
          "fluid.spacing, fluid.support_over_spacing and fluid.rest_density shape the particles: "
          "they change with a reset");
  // The lists of the last search are in the old method's order; a switch mid-run would make the
  // run depend on when it happened (and a study compares whole runs), so it needs a reset.
  require(q.neighbor_search == params_.neighbor_search,
          "engine.neighbor_search changes with a reset");
  require(q.boundary_sampling == params_.boundary_sampling,
          "engine.boundary_sampling changes with a reset");
  // The pressure means another thing to each solver (a state of the compressed fluid, or what the
  // last solve needed): a switch needs a reset.
  require(q.solver == params_.solver, "fluid.solver changes with a reset");
  // A new g changes every particle's potential energy: the ledger follows (what the fluid has been
  // given is counted in the new g from here on).
  if (q.gravity != params_.gravity) {
    double sumY = 0;
    for (const Vec3f& x : fluid_.x) sumY += double(x.y());
    ledger_.energy += sph_.mass * (q.gravity - params_.gravity) * sumY;
  }
  // A longer step places more per step: the sources and rain are checked against the limits.
  for (size_t i = 0; i < supply_.emitters.size(); ++i) {
    const std::string at = "sources[" + std::to_string(i) + "]";
    const std::string bad = checkSourceWork(supply_.emitters[i].src, q, at);
    require(bad.empty(), bad);
  }
  for (size_t r = 0; r < supply_.rain.size(); ++r) {
    const std::string at = "rain[" + std::to_string(r) + "]";
    const std::string bad = checkRainWork(supply_.rain[r].rain, rainArea(supply_.rain[r].rain), q, at);
    require(bad.empty(), bad);
  }
  // A new speed-up is the user's: it replaces what the bed guard had lowered it to.
  if (q.morphological_factor != params_.morphological_factor) factor_ = q.morphological_factor;
  params_ = resolve(q);
  sph_ = SphConstants(params_);
  dfsphK_ = DfsphConstants(sph_, params_.spacing);
  simulationBox();
  if (!effects_.surface_tension) sph_.kappa = 0;
  sediment_ = SedimentConstants(params_);
}

StepStats World::step() {
  dt_ = chooseDt();
  stepFactor_ = factorNow();
  bedStep_ = bedFast_ = 0;
  const float half = float(0.5 * dt_), full = float(dt_);
  const size_t n0 = fluid_.size();
  if (effects_.fluid_motion) {
    // The wall force (model.md) holds the water; a particle that an impact faster than the
    // penalty was made for (a tenth of the sound speed) still carries through the terrain's
    // wall surface or a closed wall is put back on it with its velocity into it removed
    // (model.md, "a hard floor under the penalty").
    const bool walls = domain_.walls;
    const Heightfield& floor = wall_.of(terrain_);
    const float xlo = float(terrain_.x0()), xhi = float(terrain_.xMax()), zlo = float(terrain_.z0()), zhi = float(terrain_.zMax());
    long contacts = 0;
    // DFSPH: the whole step's non-pressure kick, then the pressure that keeps the density at ρ0
    // after the drift; the drift below then has no kick of its own.
    const float kick = implicit() ? 0.0f : half;
    if (implicit()) {
      timed(Pass::kIntegrate, [&] {
#pragma omp parallel for schedule(static) if (n0 >= kParallelFrom)
        for (size_t i = 0; i < n0; ++i) fluid_.v[i] += full * fluid_.a[i];
      });
      timed(Pass::kPressureSolve, [&] {
        densitySolve_ = solveDensity(dfsphK_, neighbors_.fluid(), dt_, params_.max_density_error, params_.max_iterations,
                                     fluid_, dfsph_);
      });
    }
    timed(Pass::kIntegrate, [&] {
#pragma omp parallel for schedule(static) reduction(+ : contacts)
      for (size_t i = 0; i < n0; ++i) {
        if (kick != 0.0f) fluid_.v[i] += kick * fluid_.a[i];  // kick: v(t + Δt/2)
        fluid_.x[i] += full * fluid_.v[i];  // drift: x(t + Δt)
        Vec3f& x = fluid_.x[i];
        Vec3f& v = fluid_.v[i];
        if (walls) {
          if (x.x() < xlo) x.x() = xlo, v.x() = std::max(v.x(), 0.0f);
          if (x.x() > xhi) x.x() = xhi, v.x() = std::min(v.x(), 0.0f);
          if (x.z() < zlo) x.z() = zlo, v.z() = std::max(v.z(), 0.0f);
          if (x.z() > zhi) x.z() = zhi, v.z() = std::min(v.z(), 0.0f);
        }
        // Along one plane's normal a particle in a fold may land under the next triangle's
        // plane: a second look puts it on that one.
        if (putOnFloor(floor, x, v)) ++contacts, putOnFloor(floor, x, v);
      }
    });
    ledger_.terrainContacts += contacts;
  }
  emit();  // before removal: the grid's indices are those of the last search
  rain();
  removeParticles();
  ++step_;
  time_ += dt_;
  // Frozen fluid (sediment-only scenes) keeps its neighbors unless particles come or go.
  const bool moved = effects_.fluid_motion || fluid_.size() != n0;
  if (moved) {
    if (params_.reorder_every > 0 && step_ % params_.reorder_every == 0) {
      timed(Pass::kNeighborSearch, [&] {
        fluid_.gather(neighbors_.rebuildGrid(fluid_.x, float(sph_.h)).zOrder(fluid_.x));
      });
    }
    searchNeighbors();
  } else if (effects_.erosion || effects_.deposition) {
    // The terrain moved under frozen fluid: the boundary particles followed it, so their
    // neighbor lists are rebuilt (the fluid's are unchanged).
    timed(Pass::kBoundaryNeighbors, [&] { buildBoundaryLists(); });
  }
  const size_t n = fluid_.size();
  if (effects_.fluid_motion && !implicit()) {
    timed(Pass::kIntegrate, [&] {
      // The force time's velocity, predicted from the half step: v̂ = v(t+Δt/2) + Δt/2 · a(t).
      resizeForParticles(vhat_, n);
#pragma omp parallel for schedule(static) if (n >= kParallelFrom)
      for (size_t i = 0; i < n; ++i) vhat_[i] = fluid_.v[i] + half * fluid_.a[i];
    });
    computeAccelerations();
    timed(Pass::kIntegrate, [&] {
#pragma omp parallel for schedule(static) if (n >= kParallelFrom)
      for (size_t i = 0; i < n; ++i) fluid_.v[i] += half * fluid_.a[i];  // kick: v(t + Δt)
    });
  }
  // The bed's work every K-th step over the K steps' time (model.md, "the bed's work every K
  // steps"); K = 1 (validateParams keeps K ≥ 1): every step over its own.
  const bool exchange = step_ % params_.exchange_every == 0;
  const double span = double(params_.exchange_every) * dt_;
  if (exchange) sedimentWork(span);
  // DFSPH's density, α and divergence solve after the terrain moved: a saved state then holds all
  // they read, and a resumed run recomputes α from the same terrain (world_state.cpp).
  if (effects_.fluid_motion && implicit()) implicitAccelerations(true);
  if (exchange && (effects_.erosion || effects_.deposition))
    timed(Pass::kFlowMaps, [&] {
      if (!effects_.erosion) bedShear(sediment_, neighbors_.boundary(), boundary_, fluid_, sedimentWork_.tau);
      flow_.record(terrain_, vertexArea_, fluid_, sedimentWork_.tau, sediment_.volume, params_.spacing, stepFactor_ * span);
    });
  morphTime_ += stepFactor_ * dt_;
  timed(Pass::kInvariants, [&] { checkInvariants(); });
  StepStats s;
  s.dt = dt_;
  s.time = time_;
  s.morph_time = morphTime_;
  s.factor = stepFactor_;
  s.bed_step_ds = bedStep_;
  s.bed_fast_fraction = bedFast_;
  if (implicit()) {
    s.density_iterations = densitySolve_.iterations, s.density_error = densitySolve_.error;
    s.divergence_iterations = divergenceSolve_.iterations, s.divergence_error = divergenceSolve_.error;
  }
  s.step = step_;
  s.particles = n;
  float v2 = 0;
#pragma omp parallel for schedule(static) reduction(max : v2) if (n >= kParallelFrom)
  for (size_t i = 0; i < n; ++i) v2 = std::max(v2, fluid_.v[i].squaredNorm());
  s.max_speed = std::sqrt(double(v2));
  return s;
}

}  // namespace scour
