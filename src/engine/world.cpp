#include "engine/world.h"

#include "engine/limits.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <istream>
#include <ostream>
#include <sstream>
#include <type_traits>

namespace scour {

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
    case Pass::kInvariants: return "invariants";
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
    case Pass::kNoSlip: return Table1Group::kSph;
    case Pass::kBoundaryParticles:
    case Pass::kBoundaryNeighbors: return Table1Group::kBoundary;
    case Pass::kSediment:
    case Pass::kErosion:
    case Pass::kTerrain: return Table1Group::kErosion;
    default: return Table1Group::kOther;
  }
}

namespace {

SimParams resolve(SimParams p) {
  double contact = p.contact_over_spacing > 0 ? p.contact_over_spacing * p.spacing : p.spacing;
  // K_S: a particle arriving at a tenth of the sound speed is stopped within the contact distance.
  if (p.penalty_stiffness <= 0) p.penalty_stiffness = std::pow(0.1 * p.sound_speed / contact, 2);
  if (p.penalty_damping <= 0) p.penalty_damping = 2.0 * std::sqrt(p.penalty_stiffness);
  return p;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// What the walls see of the terrain: its Δs/2 envelope (WallSurface).
WallSurface wallSurfaceFor(const Heightfield& terrain, const SimParams& p) {
  return WallSurface(terrain, 0.5 * p.spacing);
}

// A source is checked against the limits (engine/limits.h) before its slots are made.
Emitter makeEmitter(const Source& src, const SimParams& p, const std::string& at) {
  require(src.radius > 0 && std::isfinite(src.radius), at + ".radius must be positive");
  require(src.rate > 0 && std::isfinite(src.rate), at + ".rate must be positive");
  require(src.direction.norm() > 0 && src.direction.allFinite(), at + ".direction must be a non-zero vector");
  require(src.center.allFinite(), at + ".position must be finite");
  require(src.start >= 0 && !(src.stop < src.start), at + ".stop must not come before its start");
  const std::string bad = checkSourceWork(src, p, at);
  require(bad.empty(), bad);
  return Emitter(src, p.spacing);
}

void validateSink(const Sink& s, const std::string& at) {
  require(s.lo.allFinite() && s.hi.allFinite() && (s.hi - s.lo).minCoeff() > 0,
          at + ": max must exceed min on every axis");
}

}  // namespace

World::World(WorldDesc d)
    : p_(resolve(d.params)),
      k_(p_),
      sk_(p_),
      hf_(std::move(d.terrain)),
      dom_(d.domain),
      fx_(d.effects),
      sinks_(std::move(d.sinks)),
      sampler_(hf_, p_.spacing) {
  std::string bad = validateParams(d.params);
  require(bad.empty(), bad);
  if (!fx_.surface_tension) k_.kappa = 0;  // the cohesion term is skipped inside the force pass
  require(hf_.nx() >= 2 && hf_.nz() >= 2, "terrain: needs at least 2 × 2 vertices");
  require(hf_.dx() > 0 && hf_.dz() > 0, "terrain: cell size must be positive");
  for (double h : hf_.heights()) require(std::isfinite(h), "terrain: heights must be finite");
  hf0_ = hf_;
  wall_ = wallSurfaceFor(hf_, p_);
  vertexArea_ = vertexAreas(hf_);
  terrainReference_ = hf_.minHeight();
  acc_.resize(hf_.triangleCount());
  require(double(hf_.heights().size()) <= Limits::kMaxTerrainVertices, "terrain: more vertices than the limit");
  maxParticles_ = size_t(particleCapacity(double(hf_.heights().size())));
  require(d.particles.size() <= maxParticles_, "particles: more than the memory limit allows");
  simulationBox();
  for (size_t s = 0; s < d.sources.size(); ++s)
    emitters_.push_back(makeEmitter(d.sources[s], p_, "sources[" + std::to_string(s) + "]"));
  for (size_t s = 0; s < sinks_.size(); ++s) validateSink(sinks_[s], "sinks[" + std::to_string(s) + "]");
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
    const std::string bad = checkRainWork(rn, rainArea(rn), p_, at);
    require(bad.empty(), bad);
    rain_.push_back(RainState{rn, 0.0, 0, 0, 0});
  }
  require(d.pressure.empty() || d.pressure.size() == d.particles.size(),
          "pressure: one value per particle expected");
  for (size_t i = 0; i < d.particles.size(); ++i) {
    require(d.particles[i].allFinite(), "particles: positions must be finite");
    double p0 = d.pressure.empty() ? 0.0 : d.pressure[i];
    require(std::isfinite(p0) && p0 >= 0, "pressure: must be finite and ≥ 0");
    f_.push(d.particles[i], Vec3f::Zero(), nextId_++, float(k_.densityFor(p0)));
  }
  require(d.concentration.empty() || d.concentration.size() == d.particles.size(),
          "concentration: one value per particle expected");
  for (size_t i = 0; i < d.concentration.size(); ++i) {
    const double c = d.concentration[i];
    require(std::isfinite(c) && c >= 0 && c <= p_.c_max, "concentration: must lie in [0, c_max]");
    f_.sed[i] = c * sk_.volume;
  }
  initialSoil_ = soilBudget().total();
  energyLedger_ = mechanicalEnergy();
  for (size_t i = 0; i < f_.size(); ++i) {
    const double c = f_.sed[i] / sk_.volume;
    inv_.c_min = i == 0 ? c : std::min(inv_.c_min, c);
    inv_.c_max = i == 0 ? c : std::max(inv_.c_max, c);
  }
  defects_.c_min_raw = inv_.c_min, defects_.c_max_raw = inv_.c_max;
  searchNeighbors();
  if (fx_.fluid_motion) computeAccelerations();  // frozen fluid: no SPH pass ever runs
}

template <class F>
void World::timed(Pass pass, F&& f) {
  auto t0 = std::chrono::steady_clock::now();
  f();
  passSeconds_[size_t(pass)] +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++passCalls_[size_t(pass)];
}

double World::chooseDt() const {
  if (p_.fixed_dt > 0) return p_.fixed_dt;
  float v2 = 0, a2 = 0, rhoMax = 0;
  const size_t n = f_.size();
#pragma omp parallel for schedule(static) reduction(max : v2, a2, rhoMax)
  for (size_t i = 0; i < n; ++i) {
    v2 = std::max(v2, f_.v[i].squaredNorm());
    a2 = std::max(a2, f_.a[i].squaredNorm());
    rhoMax = std::max(rhoMax, f_.rho[i]);
  }
  const double h = k_.h;
  double dt = p_.max_dt;
  if (fx_.fluid_motion) {
    dt = std::min(dt, p_.cfl * h / std::max(k_.soundSpeed(rhoMax), std::sqrt(double(v2))));
    if (a2 > 0) dt = std::min(dt, p_.force_cfl * std::sqrt(h / std::sqrt(double(a2))));
    if (densityRate_ > 0) dt = std::min(dt, p_.density_cfl / densityRate_);
    if (p_.viscosity > 0) dt = std::min(dt, 0.125 * h * h / p_.viscosity);
    dt = std::min(dt, 0.5 / std::sqrt(p_.penalty_stiffness));
  }
  // Explicit sediment transport: diffusion needs Δt ≤ h²/(8D) (model.md); the donor–acceptor
  // settling moves at most a fraction λ of h per step.
  if (fx_.diffusion && p_.diffusion > 0) dt = std::min(dt, 0.125 * h * h / p_.diffusion);
  if ((fx_.settling || fx_.deposition) && sk_.vs0 != 0) dt = std::min(dt, p_.cfl * h / std::abs(sk_.vs0));
  return dt;
}

void World::searchNeighbors() {
  timed(Pass::kNeighborSearch, [&] { buildFluidLists(); });
  if (!needsBoundary()) return;
  timed(Pass::kBoundaryParticles, [&] {
    if (sampler_.updateActiveTiles(hf_, f_.x, k_.h)) sampler_.generate(hf_, b_);
  });
  timed(Pass::kBoundaryNeighbors, [&] { buildBoundaryLists(); });
}

void World::buildFluidLists() {
  if (p_.neighbor_search == NeighborSearch::kKdTree) {
    // The paper's kd-tree, rebuilt every step; the same sets as the grid, in ascending index.
    fluidTree_.build(f_.x);
    nbrs_.build(fluidTree_, f_.x, float(k_.h), true);
    gridStale_ = true;
    return;
  }
  grid_.build(f_.x, float(k_.h));
  nbrs_.build(grid_, f_.x, f_.x, grid_.start(), grid_.sorted(), float(k_.h), true);
  gridStale_ = false;
}

void World::buildBoundaryLists() {
  if (p_.neighbor_search == NeighborSearch::kKdTree) {
    boundaryTree_.build(b_.x);
    bnbrs_.build(boundaryTree_, f_.x, float(k_.h), false);
    return;
  }
  grid_.binOther(b_.x, bstart_, bsorted_);
  bnbrs_.build(grid_, f_.x, b_.x, bstart_, bsorted_, float(k_.h), false);
}

void World::ensurePlacementGrid() {
  if (!gridStale_) return;
  grid_.build(f_.x, float(k_.h));
  gridStale_ = false;
}

void World::computeAccelerations() {
  if (vhat_.size() != f_.size()) vhat_ = f_.v;
  timed(Pass::kDensity, [&] {
    if (k_.continuity)
      // f_.v holds v(t + Δt/2) here
      densityRate_ = integrateDensity(k_, nbrs_, wall_.of(hf_), dom_, f_.v, dt_, f_);
    else
      // No continuity rate to bound Δt.
      computeDensity(k_, nbrs_, wall_.of(hf_), dom_, f_), densityRate_ = 0;
  });
  timed(Pass::kForces, [&] { computeForces(k_, nbrs_, vhat_, f_); });
  timed(Pass::kBoundaryForces, [&] { applyBoundaryForces(k_, wall_.of(hf_), dom_, vhat_, f_); });
  if (fx_.no_slip) timed(Pass::kNoSlip, [&] { applyNoSlip(k_, bnbrs_, b_, vhat_, f_); });
}

void World::removeParticles() {
  const bool open = !dom_.walls;
  const bool sinking = fx_.sinks && !sinks_.empty();
  if (!sinking && !open) return;
  timed(Pass::kSinks, [&] {
    std::vector<uint32_t> keep;
    keep.reserve(f_.size());
    for (size_t i = 0; i < f_.size(); ++i) {
      const Vec3f& x = f_.x[i];
      bool sunk = false;
      if (sinking)
        for (const Sink& s : sinks_) sunk = sunk || s.contains(x);
      bool out = open && (x.x() < hf_.x0() || x.x() > hf_.xMax() || x.z() < hf_.z0() ||
                          x.z() > hf_.zMax());
      if (sunk || out) removedSediment_ += f_.sed[i], energyLedger_ -= particleEnergy(i);
      if (sunk) ++removedSinks_;
      else if (out) ++removedOutflow_;
      else keep.push_back(uint32_t(i));
    }
    if (keep.size() != f_.size()) f_.gather(keep);
  });
}

double World::rainArea(const Rain& r) const {
  return scour::rainArea(r, hf_.x0(), hf_.xMax(), hf_.z0(), hf_.zMax());
}

void World::simulationBox() {
  const double pad = std::max(hf_.xMax() - hf_.x0(), hf_.zMax() - hf_.z0());
  const double climb = p_.sound_speed * p_.sound_speed / (2 * std::max(p_.gravity, 0.1));
  boxLo_ = Vec3f(float(hf_.x0() - pad), float(hf_.minHeight() - pad), float(hf_.z0() - pad));
  boxHi_ = Vec3f(float(hf_.xMax() + pad), float(hf_.maxHeight() + pad + climb), float(hf_.zMax() + pad));
}

bool World::place(const Vec3f& pos, const Vec3f& vel, double clearance) {
  if (f_.size() >= maxParticles_) {
    std::ostringstream o;
    o << "step " << step_ << " (t = " << time_ << " s): " << f_.size()
      << " particles, the most the memory limit of " << Limits::kMaxBytes / 1e9
      << " GB allows next to this terrain: sources and rain stop the run here";
    throw LimitExceeded(o.str());
  }
  // The grid indexes the particles that existed at the last search; they have moved by far less
  // than a cell since, so its 27 cells still hold every particle within a clearance (≤ Δs) of
  // pos. Particles placed since (index ≥ the grid's count: this step's drops and layers, the
  // brush's) are checked one by one; there are few.
  ensurePlacementGrid();
  // Never inside a closed wall's contact zone: the wall's spring would hand the new particle
  // energy no source supplied (`scour stress`, edge-source and cloudburst).
  if (dom_.walls) {
    const double m = wallMargin() - 1e-4 * p_.spacing;  // float rounding of a drop at the margin
    if (pos.x() < hf_.x0() + m || pos.x() > hf_.xMax() - m || pos.z() < hf_.z0() + m ||
        pos.z() > hf_.zMax() - m)
      return false;
  }
  const float r2 = float(clearance * clearance * p_.spacing * p_.spacing);
  const size_t indexed = grid_.particleCount();
  bool occupied = false;
  grid_.forEachCandidate(pos, grid_.start(), grid_.sorted(), [&](uint32_t j) {
    occupied = occupied || (j < indexed && (f_.x[j] - pos).squaredNorm() < r2);
  });
  for (size_t j = indexed; j < f_.size() && !occupied; ++j)
    occupied = (f_.x[j] - pos).squaredNorm() < r2;
  if (occupied) return false;
  f_.push(pos, vel, nextId_++, float(p_.rest_density));
  vhat_.push_back(vel);
  energyLedger_ += particleEnergy(f_.size() - 1);
  return true;
}

double World::particleEnergy(size_t i) const {
  return k_.mass * (0.5 * double(f_.v[i].squaredNorm()) + p_.gravity * double(f_.x[i].y()));
}

double World::mechanicalEnergy() const {
  double e = 0;  // a fixed-order sum, like every other reduction here
  for (size_t i = 0; i < f_.size(); ++i) e += particleEnergy(i);
  return e;
}

void World::emit() {
  if (emitters_.empty() || !fx_.sources) return;
  timed(Pass::kSources, [&] {
    for (Emitter& e : emitters_) {
      if (time_ < e.src.start || time_ >= e.src.stop) continue;
      e.travelled += e.speed * dt_;
      while (e.travelled >= p_.spacing) {
        e.travelled -= p_.spacing;
        const Eigen::Vector3d base = e.src.center + e.src.direction * e.travelled;
        const Vec3f vel = (e.src.direction * e.speed).cast<float>();
        for (const auto& off : e.slots) {
          const bool placed = place((base + off).cast<float>(), vel, kEmitClearance);
          ++(placed ? e.emitted : e.blocked);
          emittedTotal_ += placed;
        }
      }
    }
  });
}

void World::rain() {
  if (rain_.empty() || !fx_.rain) return;
  timed(Pass::kRain, [&] {
    const double drop = p_.spacing * p_.spacing * p_.spacing;
    for (RainState& r : rain_) {
      const Rain& rn = r.rain;
      if (time_ < rn.start || time_ >= rn.stop) continue;
      const double metresPerSecond = rn.intensity_mm_h / 3.6e6;
      // Rain falls on the part of its rectangle over the terrain, at its intensity: a rectangle
      // larger than the domain brings the domain's share, not its whole volume.
      r.pending += metresPerSecond * rainArea(rn) * dt_;
      while (r.pending >= drop) {
        r.pending -= drop;
        const auto [u, w] = RainState::point(rn.seed, r.drawn++);
        // With closed walls the drops fall on that part less the walls' contact zone (the same
        // volume, spread uniformly over the rest).
        double lx = std::max(rn.lo_x, hf_.x0()), hx = std::min(rn.hi_x, hf_.xMax());
        double lz = std::max(rn.lo_z, hf_.z0()), hz = std::min(rn.hi_z, hf_.zMax());
        if (dom_.walls) {
          const double m = wallMargin();
          lx = std::max(lx, hf_.x0() + m), hx = std::min(hx, hf_.xMax() - m);
          lz = std::max(lz, hf_.z0() + m), hz = std::min(hz, hf_.zMax() - m);
        }
        const double x = lx + u * (hx - lx), z = lz + w * (hz - lz);
        const double y = hf_.heightAt(x, z) + std::max(rn.drop_height, p_.spacing);
        const bool placed = place(Vec3f(float(x), float(y), float(z)), Vec3f(0, -float(rn.drop_speed), 0));
        ++(placed ? r.emitted : r.blocked);
        emittedTotal_ += placed;
      }
    }
  });
}

void World::sedimentWork() {
  SedimentEffects sfx{fx_.settling, fx_.diffusion, fx_.deposition, fx_.erosion};
  if (sfx.settling || sfx.diffusion || sfx.deposition) {
    timed(Pass::kSediment, [&] {
      transferSediment(sk_, sfx, nbrs_, bnbrs_, b_, dt_, f_, acc_, sedimentWork_);
      const SedimentDefects& d = sedimentWork_.defects;
      if (sk_.advection == SettlingAdvection::kNaiveGradient && sfx.settling && f_.size() > 0) {
        defects_.created += d.created;
        defects_.clipped += d.clipped;
        defects_.c_min_raw = std::min(defects_.c_min_raw, d.c_min_raw);
        defects_.c_max_raw = std::max(defects_.c_max_raw, d.c_max_raw);
      }
    });
  }
  if (sfx.erosion) timed(Pass::kErosion, [&] { erode(sk_, bnbrs_, b_, dt_, f_, acc_); });
  if (sfx.erosion || sfx.deposition) {
    timed(Pass::kTerrain, [&] {
      std::vector<int> moved = applyTerrainChange(hf_, vertexArea_, acc_);
      BoundarySampler::follow(hf_, moved, b_);
      wall_.follow(hf_, moved);
    });
  }
}

void World::setParams(const SimParams& q) {
  std::string bad = validateParams(q);
  require(bad.empty(), bad);
  require(q.spacing == p_.spacing && q.support_over_spacing == p_.support_over_spacing &&
              q.rest_density == p_.rest_density,
          "fluid.spacing, fluid.support_over_spacing and fluid.rest_density shape the particles: "
          "they change with a reset");
  // The lists of the last search are in the old method's order; a switch mid-run would make the
  // run depend on when it happened (and a study compares whole runs), so it needs a reset.
  require(q.neighbor_search == p_.neighbor_search,
          "engine.neighbor_search changes with a reset");
  // A new g changes every particle's potential energy: the ledger follows (what the fluid has been
  // given is counted in the new g from here on).
  if (q.gravity != p_.gravity) {
    double sumY = 0;
    for (const Vec3f& x : f_.x) sumY += double(x.y());
    energyLedger_ += k_.mass * (q.gravity - p_.gravity) * sumY;
  }
  // A longer step places more per step: the sources and rain are checked against the limits.
  for (size_t i = 0; i < emitters_.size(); ++i) {
    const std::string at = "sources[" + std::to_string(i) + "]";
    const std::string bad = checkSourceWork(emitters_[i].src, q, at);
    require(bad.empty(), bad);
  }
  for (size_t r = 0; r < rain_.size(); ++r) {
    const std::string at = "rain[" + std::to_string(r) + "]";
    const std::string bad = checkRainWork(rain_[r].rain, rainArea(rain_[r].rain), q, at);
    require(bad.empty(), bad);
  }
  p_ = resolve(q);
  k_ = SphConstants(p_);
  simulationBox();
  if (!fx_.surface_tension) k_.kappa = 0;
  sk_ = SedimentConstants(p_);
}

std::vector<Source> World::sources() const {
  std::vector<Source> out;
  for (const Emitter& e : emitters_) out.push_back(e.src);
  return out;
}

size_t World::addSource(const Source& s) {
  emitters_.push_back(makeEmitter(s, p_, "source"));
  return emitters_.size() - 1;
}

void World::updateSource(size_t i, const Source& s) {
  require(i < emitters_.size(), "source " + std::to_string(i) + " does not exist");
  Emitter next = makeEmitter(s, p_, "source");
  const long emitted = emitters_[i].emitted, blocked = emitters_[i].blocked;
  emitters_[i] = std::move(next);
  emitters_[i].emitted = emitted, emitters_[i].blocked = blocked;
}

void World::removeSource(size_t i) {
  require(i < emitters_.size(), "source " + std::to_string(i) + " does not exist");
  emitters_.erase(emitters_.begin() + long(i));
}

size_t World::addSink(const Sink& s) {
  require(s.lo.allFinite() && s.hi.allFinite() && (s.hi - s.lo).minCoeff() > 0,
          "sink: max must exceed min on every axis");
  sinks_.push_back(s);
  return sinks_.size() - 1;
}

void World::updateSink(size_t i, const Sink& s) {
  require(i < sinks_.size(), "sink " + std::to_string(i) + " does not exist");
  require(s.lo.allFinite() && s.hi.allFinite() && (s.hi - s.lo).minCoeff() > 0,
          "sink: max must exceed min on every axis");
  sinks_[i] = s;
}

void World::removeSink(size_t i) {
  require(i < sinks_.size(), "sink " + std::to_string(i) + " does not exist");
  sinks_.erase(sinks_.begin() + long(i));
}

long World::addWater(const Eigen::Vector3d& centre, double radius) {
  require(centre.allFinite() && std::isfinite(radius) && radius > 0, "water brush: needs a finite centre and radius > 0");
  const double ds = p_.spacing;
  const double reach = 2 * std::ceil(radius / ds) + 1;
  require(reach * reach * reach <= Limits::kMaxPlacedPerStep,
          "water brush: a radius of " + std::to_string(radius) + " m is more than " +
              std::to_string(long(Limits::kMaxPlacedPerStep)) + " lattice points at this spacing");
  const int n = int(std::ceil(radius / ds));
  // On the lattice of spacing Δs through the centre, so repeated strokes fill rather than pile up.
  const Eigen::Vector3d base = (centre / ds).array().round() * ds;
  long added = 0;
  for (int k = -n; k <= n; ++k)
    for (int j = -n; j <= n; ++j)
      for (int i = -n; i <= n; ++i) {
        const Eigen::Vector3d x = base + ds * Eigen::Vector3d(i, j, k);
        if ((x - centre).norm() > radius) continue;
        if (x.x() < hf_.x0() || x.x() > hf_.xMax() || x.z() < hf_.z0() || x.z() > hf_.zMax()) continue;
        if (x.y() < hf_.heightAt(x.x(), x.z()) + 0.5 * ds) continue;
        added += place(x.cast<float>(), Vec3f::Zero(), 0.95);  // water at rest: a full Δs apart
      }
  paintedTotal_ += added;  // the brush is not a source: counted apart
  return added;
}

SoilBudget World::soilBudget() const {
  SoilBudget s;
  s.terrain = terrainVolume(hf_, vertexArea_, terrainReference_);
  for (double v : f_.sed) s.suspended += v;
  s.removed = removedSediment_;
  s.initial = initialSoil_;
  s.created = defects_.created;
  return s;
}

std::vector<double> World::heightChange() const {
  std::vector<double> d(hf_.heights().size());
  for (size_t i = 0; i < d.size(); ++i) d[i] = hf_.heights()[i] - hf0_.heights()[i];
  return d;
}

long World::blockedSlots() const {
  long s = 0;
  for (const auto& e : emitters_) s += e.blocked;
  return s;
}

StepStats World::step() {
  dt_ = chooseDt();
  const float half = float(0.5 * dt_), full = float(dt_);
  const size_t n0 = f_.size();
  if (fx_.fluid_motion) {
    // Closed walls: the wall force (model.md) holds the water; a particle that a violent impact
    // still carries through is put back on the wall with its outward velocity removed.
    const bool walls = dom_.walls;
    const float xlo = float(hf_.x0()), xhi = float(hf_.xMax()), zlo = float(hf_.z0()), zhi = float(hf_.zMax());
    timed(Pass::kIntegrate, [&] {
#pragma omp parallel for schedule(static)
      for (size_t i = 0; i < n0; ++i) {
        f_.v[i] += half * f_.a[i];  // kick: v(t + Δt/2)
        f_.x[i] += full * f_.v[i];  // drift: x(t + Δt)
        if (walls) {
          Vec3f& x = f_.x[i];
          Vec3f& v = f_.v[i];
          if (x.x() < xlo) x.x() = xlo, v.x() = std::max(v.x(), 0.0f);
          if (x.x() > xhi) x.x() = xhi, v.x() = std::min(v.x(), 0.0f);
          if (x.z() < zlo) x.z() = zlo, v.z() = std::max(v.z(), 0.0f);
          if (x.z() > zhi) x.z() = zhi, v.z() = std::min(v.z(), 0.0f);
        }
      }
    });
  }
  emit();  // before removal: the grid's indices are those of the last search
  rain();
  removeParticles();
  ++step_;
  time_ += dt_;
  // Frozen fluid (sediment-only scenes) keeps its neighbors unless particles come or go.
  const bool moved = fx_.fluid_motion || f_.size() != n0;
  if (moved) {
    if (p_.reorder_every > 0 && step_ % p_.reorder_every == 0) {
      timed(Pass::kNeighborSearch, [&] {
        grid_.build(f_.x, float(k_.h));
        f_.gather(grid_.zOrder(f_.x));
      });
    }
    searchNeighbors();
  } else if (fx_.erosion || fx_.deposition) {
    // The terrain moved under frozen fluid: the boundary particles followed it, so their
    // neighbor lists are rebuilt (the fluid's are unchanged).
    timed(Pass::kBoundaryNeighbors, [&] { buildBoundaryLists(); });
  }
  const size_t n = f_.size();
  if (fx_.fluid_motion) {
    timed(Pass::kIntegrate, [&] {
      // The force time's velocity, predicted from the half step: v̂ = v(t+Δt/2) + Δt/2 · a(t).
      vhat_.resize(n);
#pragma omp parallel for schedule(static)
      for (size_t i = 0; i < n; ++i) vhat_[i] = f_.v[i] + half * f_.a[i];
    });
    computeAccelerations();
    timed(Pass::kIntegrate, [&] {
#pragma omp parallel for schedule(static)
      for (size_t i = 0; i < n; ++i) f_.v[i] += half * f_.a[i];  // kick: v(t + Δt)
    });
  }
  sedimentWork();
  timed(Pass::kInvariants, [&] { checkInvariants(); });
  StepStats s;
  s.dt = dt_;
  s.time = time_;
  s.step = step_;
  s.particles = n;
  float v2 = 0;
#pragma omp parallel for schedule(static) reduction(max : v2)
  for (size_t i = 0; i < n; ++i) v2 = std::max(v2, f_.v[i].squaredNorm());
  s.max_speed = std::sqrt(double(v2));
  return s;
}

void World::checkInvariants() {
  const size_t n = f_.size();
  const double ds = p_.spacing, slack = 0.5 * ds;
  // First offending particle (lowest index) of each kind, found in parallel, reported in order.
  long badNan = -1, badOut = -1, badBox = -1;
  double deepest = -1e300;
  long deepestAt = -1;
  auto upd = [](long& slot, long i) {
#pragma omp critical(scour_inv)
    if (slot < 0 || i < slot) slot = i;
  };
#pragma omp parallel
  {
    double tdeep = -1e300;
    long tat = -1;
#pragma omp for schedule(static) nowait
    for (size_t i = 0; i < n; ++i) {
      const Vec3f& x = f_.x[i];
      if (!x.allFinite() || !f_.v[i].allFinite() || !f_.a[i].allFinite()) {
        upd(badNan, long(i));
        continue;
      }
      // Depth across the terrain (along its normal): the vertical one would call a particle
      // touching a near-vertical cliff face deep inside it. Below a steep triangle (a riser
      // narrower than a cell) its plane is no measure: the distance to the surface around.
      const SurfacePoint sp = hf_.surface(x.x(), x.z());
      double depth = (sp.height - x.y()) * sp.normal.y() / ds;
      if (depth > 0 && sp.normal.y() < 0.5) depth = hf_.distanceToSurface(x.cast<double>()) / ds;
      if (depth > tdeep || (depth == tdeep && long(i) < tat)) tdeep = depth, tat = long(i);
      if (dom_.walls && (x.x() < hf_.x0() - slack || x.x() > hf_.xMax() + slack ||
                         x.z() < hf_.z0() - slack || x.z() > hf_.zMax() + slack))
        upd(badOut, long(i));
      if ((x.array() < boxLo_.array()).any() || (x.array() > boxHi_.array()).any()) upd(badBox, long(i));
    }
#pragma omp critical(scour_inv_deep)
    if (tdeep > deepest || (tdeep == deepest && tat < deepestAt)) deepest = tdeep, deepestAt = tat;
  }
  inv_.max_penetration_over_ds = std::max(inv_.max_penetration_over_ds, std::max(deepest, 0.0));
  long badC = -1;
  for (size_t i = 0; i < n; ++i) {
    const double c = f_.sed[i] / sk_.volume;
    inv_.c_min = std::min(inv_.c_min, c);
    inv_.c_max = std::max(inv_.c_max, c);
    if (badC < 0 && (c < -1e-12 || c > p_.c_max * (1 + 1e-12))) badC = long(i);
  }
  auto where = [&](long i) {
    std::ostringstream o;
    const Vec3f& x = f_.x[i];
    o << "step " << step_ << " (t = " << time_ << " s): particle " << i << " (id " << f_.id[i]
      << ") at (" << x.x() << ", " << x.y() << ", " << x.z() << ")";
    return o.str();
  };
  if (badNan >= 0) {
    ++inv_.nan;
    const Vec3f& v = f_.v[badNan];
    std::ostringstream o;
    o << where(badNan) << " has a non-finite state: velocity (" << v.x() << ", " << v.y() << ", "
      << v.z() << ")";
    throw InvariantViolation(o.str());
  }
  if (badBox >= 0) {
    const Vec3f& v = f_.v[badBox];
    std::ostringstream o;
    o << where(badBox) << " left the simulation box (the terrain grown by its size on every side) "
      << "at speed " << v.norm() << " m/s: the run blew up";
    throw InvariantViolation(o.str());
  }
  // The soil budget, summed from scratch (every vertex, every particle) when soil can move.
  if (fx_.erosion || fx_.deposition || fx_.settling || fx_.diffusion) {
    const SoilBudget soil = soilBudget();
    const double err = soil.relativeError();
    inv_.soil_relative_error = std::max(inv_.soil_relative_error, err);
    if (!(err <= kSoilTolerance)) {
      std::ostringstream o;
      o << "step " << step_ << " (t = " << time_ << " s): the soil budget is off by " << err
        << " relative (terrain " << soil.terrain << " + suspended " << soil.suspended
        << " + removed " << soil.removed << " m³ against " << soil.initial << " m³ at the start)";
      throw InvariantViolation(o.str());
    }
  }
  if (badC >= 0) {
    std::ostringstream o;
    o << where(badC) << " carries sediment concentration C = " << f_.sed[badC] / sk_.volume
      << " outside [0, " << p_.c_max << "]";
    throw InvariantViolation(o.str());
  }
  if (badOut >= 0) {
    ++inv_.escaped;
    throw InvariantViolation(where(badOut) + " has left the domain through a closed wall");
  }
  if (deepest > p_.max_penetration_over_ds) {
    std::ostringstream o;
    o << where(deepestAt) << " is " << deepest << " Δs below the terrain (limit "
      << p_.max_penetration_over_ds << " Δs)";
    throw InvariantViolation(o.str());
  }
}

uint64_t World::stateHash() const {
  uint64_t h = 1469598103934665603ULL;
  auto mix = [&](const void* data, size_t bytes) {
    const auto* c = static_cast<const unsigned char*>(data);
    for (size_t k = 0; k < bytes; ++k) h = (h ^ c[k]) * 1099511628211ULL;
  };
  uint64_t n = f_.size();
  mix(&n, sizeof n);
  mix(f_.x.data(), n * sizeof(Vec3f));
  mix(f_.v.data(), n * sizeof(Vec3f));
  mix(f_.sed.data(), n * sizeof(double));
  mix(hf_.heights().data(), hf_.heights().size() * sizeof(double));
  mix(&time_, sizeof time_);
  return h;
}

namespace {

template <class T>
void put(std::ostream& o, const T& v) {
  static_assert(std::is_trivially_copyable_v<T>);
  o.write(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
void putVec(std::ostream& o, const std::vector<T>& v) {
  put(o, uint64_t(v.size()));
  o.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(T)));
}
template <class T>
void get(std::istream& in, T& v, const char* what) {
  in.read(reinterpret_cast<char*>(&v), sizeof v);
  if (!in) throw std::runtime_error(std::string("state ends early (in ") + what + ")");
}
template <class T>
void getVec(std::istream& in, std::vector<T>& v, const char* what, uint64_t expect = UINT64_MAX) {
  uint64_t n = 0;
  get(in, n, what);
  if (expect != UINT64_MAX && n != expect)
    throw std::runtime_error(std::string("state does not fit this scene (") + what + ": " +
                             std::to_string(n) + " entries, the scene has " +
                             std::to_string(expect) + ")");
  // Never more than the bytes that are left: a corrupt count cannot ask for memory.
  const std::streampos here = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff left = in.tellg() - here;
  in.seekg(here);
  if (!in || left < 0 || n > uint64_t(left) / sizeof(T))
    throw std::runtime_error(std::string("state is corrupt (") + what + ": " + std::to_string(n) +
                             " entries, more than the state holds)");
  v.resize(n);
  in.read(reinterpret_cast<char*>(v.data()), std::streamsize(n * sizeof(T)));
  if (!in) throw std::runtime_error(std::string("state ends early (in ") + what + ")");
}

constexpr uint32_t kStateTag = 0x444C5257;  // "WRLD"
// Version 2 adds the sediment defects (naive advection), version 3 the last density rate (the
// next Δt's bound); older states load with none.
constexpr uint32_t kStateVersion = 3;

}  // namespace

void World::saveState(std::ostream& o) const {
  put(o, kStateTag);
  put(o, kStateVersion);
  putVec(o, f_.x), putVec(o, f_.v), putVec(o, f_.a), putVec(o, f_.rho), putVec(o, f_.p);
  putVec(o, f_.id), putVec(o, f_.sed), putVec(o, vhat_);
  putVec(o, hf_.heights());
  putVec(o, b_.x), putVec(o, b_.triangle), putVec(o, b_.area), putVec(o, b_.bary);
  putVec(o, sampler_.activeTiles());
  put(o, uint64_t(emitters_.size()));
  for (const Emitter& e : emitters_) put(o, e.travelled), put(o, e.emitted), put(o, e.blocked);
  put(o, uint64_t(rain_.size()));
  for (const RainState& r : rain_) put(o, r.pending), put(o, r.drawn), put(o, r.emitted), put(o, r.blocked);
  put(o, time_), put(o, dt_), put(o, step_), put(o, nextId_);
  put(o, removedSinks_), put(o, removedOutflow_), put(o, emittedTotal_), put(o, removedSediment_);
  put(o, paintedTotal_);
  put(o, inv_);
  put(o, defects_);
  put(o, densityRate_);
}

void World::loadState(std::istream& in) {
  uint32_t tag = 0, version = 0;
  get(in, tag, "header");
  get(in, version, "header");
  if (tag != kStateTag) throw std::runtime_error("not a Scour world state");
  if (version < 1 || version > kStateVersion)
    throw std::runtime_error("world state version " + std::to_string(version) +
                             ", this build reads versions 1 to " + std::to_string(kStateVersion));
  Fluid f;
  getVec(in, f.x, "positions");
  const uint64_t n = f.x.size();
  getVec(in, f.v, "velocities", n), getVec(in, f.a, "accelerations", n);
  getVec(in, f.rho, "densities", n), getVec(in, f.p, "pressures", n);
  getVec(in, f.id, "ids", n), getVec(in, f.sed, "sediment", n);
  std::vector<Vec3f> vhat;
  getVec(in, vhat, "predicted velocities");  // empty while the fluid is frozen
  if (!vhat.empty() && vhat.size() != n) throw std::runtime_error("state is corrupt (predicted velocities)");
  for (size_t i = 0; i < n; ++i)
    if (!f.x[i].allFinite() || !f.v[i].allFinite() || !std::isfinite(f.rho[i]) || !(f.rho[i] > 0) ||
        !std::isfinite(f.sed[i]) || f.sed[i] < 0)
      throw std::runtime_error("state is corrupt (particle " + std::to_string(i) + " is not finite)");
  std::vector<double> heights;
  getVec(in, heights, "terrain heights", hf_.heights().size());
  for (double h : heights)
    if (!std::isfinite(h)) throw std::runtime_error("state is corrupt (a terrain height is not finite)");
  BoundaryParticles b;
  getVec(in, b.x, "boundary particles");
  const uint64_t nb = b.x.size();
  getVec(in, b.triangle, "boundary triangles", nb), getVec(in, b.area, "boundary areas", nb);
  getVec(in, b.bary, "boundary coordinates", nb);
  for (int t : b.triangle)
    if (t < 0 || t >= hf_.triangleCount()) throw std::runtime_error("state is corrupt (boundary triangle)");
  std::vector<int> tiles;
  getVec(in, tiles, "active tiles");
  for (int t : tiles)
    if (t < 0 || t >= sampler_.tileCount()) throw std::runtime_error("state is corrupt (tile)");
  uint64_t count = 0;
  get(in, count, "sources");
  if (count != emitters_.size())
    throw std::runtime_error("state does not fit this scene (" + std::to_string(count) +
                             " sources, the scene has " + std::to_string(emitters_.size()) + ")");
  for (Emitter& e : emitters_) get(in, e.travelled, "sources"), get(in, e.emitted, "sources"), get(in, e.blocked, "sources");
  get(in, count, "rain");
  if (count != rain_.size())
    throw std::runtime_error("state does not fit this scene (" + std::to_string(count) +
                             " rain regions, the scene has " + std::to_string(rain_.size()) + ")");
  for (RainState& r : rain_)
    get(in, r.pending, "rain"), get(in, r.drawn, "rain"), get(in, r.emitted, "rain"), get(in, r.blocked, "rain");
  get(in, time_, "clock"), get(in, dt_, "clock"), get(in, step_, "clock"), get(in, nextId_, "clock");
  get(in, removedSinks_, "counters"), get(in, removedOutflow_, "counters");
  get(in, emittedTotal_, "counters"), get(in, removedSediment_, "counters");
  get(in, paintedTotal_, "counters");
  get(in, inv_, "invariants");
  defects_ = {};
  densityRate_ = 0;
  if (version >= 2) get(in, defects_, "sediment defects");
  if (version >= 3) get(in, densityRate_, "density rate");
  f.scratch.clear();
  f_ = std::move(f);
  vhat_ = std::move(vhat);
  hf_.heights() = std::move(heights);
  wall_ = wallSurfaceFor(hf_, p_);
  b_ = std::move(b);
  sampler_.setActiveTiles(std::move(tiles));
  energyLedger_ = mechanicalEnergy();
  // The neighbor lists of the last search: the particles have not moved since it (a step ends
  // with a kick), and the boundary lists are rebuilt on the boundary particles' places.
  buildFluidLists();
  if (needsBoundary()) buildBoundaryLists();
}

size_t World::memoryBytes() const {
  // x v a vhat, rho p scratch, id, sed
  size_t per = sizeof(Vec3f) * 4 + sizeof(float) * 3 + sizeof(uint32_t) + sizeof(double);
  return f_.x.capacity() * per + grid_.bytes() + fluidTree_.bytes() + boundaryTree_.bytes() +
         nbrs_.bytes() + bnbrs_.bytes() +
         b_.x.capacity() * (sizeof(Vec3f) + sizeof(int) + sizeof(double) + sizeof(Eigen::Vector2f)) +
         (bstart_.capacity() + bsorted_.capacity()) * sizeof(uint32_t) +
         (sedimentWork_.conc.capacity() + sedimentWork_.hind.capacity() +
          sedimentWork_.pairGeometry.capacity()) * sizeof(float) +
         sedimentWork_.scale.capacity() * sizeof(SedimentWorkspace::Scales) +
         sedimentWork_.delta.capacity() * sizeof(double) +
         sedimentWork_.pairOffset.capacity() * sizeof(size_t);
}

}  // namespace scour
