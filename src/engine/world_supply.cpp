// The World's particle supply: sources, rain and the brush place particles; sinks and open walls
// take them out; each placement and removal is entered in the ledgers (world_ledger.cpp).
#include "engine/world.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/limits.h"
#include "engine/world_parts.h"

namespace scour {

namespace detail {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

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

}  // namespace detail

using detail::makeEmitter;
using detail::require;
using detail::validateSink;

void World::removeParticles() {
  const bool open = !domain_.walls;
  const bool sinking = effects_.sinks && !supply_.sinks.empty();
  if (!sinking && !open) return;
  timed(Pass::kSinks, [&] {
    std::vector<uint32_t> keep;
    keep.reserve(fluid_.size());
    for (size_t i = 0; i < fluid_.size(); ++i) {
      const Vec3f& x = fluid_.x[i];
      bool sunk = false;
      if (sinking)
        for (const Sink& s : supply_.sinks) sunk = sunk || s.contains(x);
      bool out = open && (x.x() < terrain_.x0() || x.x() > terrain_.xMax() || x.z() < terrain_.z0() ||
                          x.z() > terrain_.zMax());
      if (sunk || out) ledger_.removedSediment += fluid_.sed[i], ledger_.energy -= particleEnergy(i);
      if (sunk) ++ledger_.removedBySinks;
      else if (out) ++ledger_.removedByOutflow;
      else keep.push_back(uint32_t(i));
    }
    if (keep.size() != fluid_.size()) fluid_.gather(keep);
  });
}

double World::rainArea(const Rain& r) const {
  return scour::rainArea(r, terrain_.x0(), terrain_.xMax(), terrain_.z0(), terrain_.zMax());
}

bool World::place(const Vec3f& pos, const Vec3f& vel, double clearance) {
  if (fluid_.size() >= supply_.maxParticles) {
    std::ostringstream o;
    o << "step " << step_ << " (t = " << time_ << " s): " << fluid_.size()
      << " particles, the most the memory limit of " << Limits::kMaxBytes / 1e9
      << " GB allows next to this terrain: sources and rain stop the run here";
    throw LimitExceeded(o.str());
  }
  // The grid indexes the particles that existed at the last search; they have moved by far less
  // than a cell since, so its 27 cells still hold every particle within a clearance (≤ Δs) of
  // pos. Particles placed since (index ≥ the grid's count: this step's drops and layers, the
  // brush's) are checked one by one; there are few.
  const Grid& grid = neighbors_.placementGrid(fluid_.x, float(sph_.h));
  // Never inside a closed wall's contact zone: the wall's spring would hand the new particle
  // energy no source supplied (`scour stress`, edge-source and cloudburst).
  if (domain_.walls) {
    const double m = wallMargin() - 1e-4 * params_.spacing;  // float rounding of a drop at the margin
    if (pos.x() < terrain_.x0() + m || pos.x() > terrain_.xMax() - m || pos.z() < terrain_.z0() + m ||
        pos.z() > terrain_.zMax() - m)
      return false;
  }
  const float r2 = float(clearance * clearance * params_.spacing * params_.spacing);
  const size_t indexed = grid.particleCount();
  bool occupied = false;
  grid.forEachCandidate(pos, grid.start(), grid.sorted(), [&](uint32_t j) {
    occupied = occupied || (j < indexed && (fluid_.x[j] - pos).squaredNorm() < r2);
  });
  for (size_t j = indexed; j < fluid_.size() && !occupied; ++j)
    occupied = (fluid_.x[j] - pos).squaredNorm() < r2;
  if (occupied) return false;
  fluid_.push(pos, vel, supply_.nextId++, float(params_.rest_density));
  vhat_.push_back(vel);
  ledger_.energy += particleEnergy(fluid_.size() - 1);
  return true;
}

void World::emit() {
  if (supply_.emitters.empty() || !effects_.sources) return;
  timed(Pass::kSources, [&] {
    for (Emitter& e : supply_.emitters) {
      if (time_ < e.src.start || time_ >= e.src.stop) continue;
      e.travelled += e.speed * dt_;
      while (e.travelled >= params_.spacing) {
        e.travelled -= params_.spacing;
        const Eigen::Vector3d base = e.src.center + e.src.direction * e.travelled;
        const Vec3f vel = (e.src.direction * e.speed).cast<float>();
        for (const auto& off : e.slots) {
          const bool placed = place((base + off).cast<float>(), vel, kEmitClearance);
          ++(placed ? e.emitted : e.blocked);
          ledger_.emitted += placed;
        }
      }
    }
  });
}

void World::rain() {
  if (supply_.rain.empty() || !effects_.rain) return;
  timed(Pass::kRain, [&] {
    const double drop = params_.spacing * params_.spacing * params_.spacing;
    for (RainState& r : supply_.rain) {
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
        double lx = std::max(rn.lo_x, terrain_.x0()), hx = std::min(rn.hi_x, terrain_.xMax());
        double lz = std::max(rn.lo_z, terrain_.z0()), hz = std::min(rn.hi_z, terrain_.zMax());
        if (domain_.walls) {
          const double m = wallMargin();
          lx = std::max(lx, terrain_.x0() + m), hx = std::min(hx, terrain_.xMax() - m);
          lz = std::max(lz, terrain_.z0() + m), hz = std::min(hz, terrain_.zMax() - m);
        }
        const double x = lx + u * (hx - lx), z = lz + w * (hz - lz);
        const double y = terrain_.heightAt(x, z) + std::max(rn.drop_height, params_.spacing);
        const bool placed = place(Vec3f(float(x), float(y), float(z)), Vec3f(0, -float(rn.drop_speed), 0));
        ++(placed ? r.emitted : r.blocked);
        ledger_.emitted += placed;
      }
    }
  });
}

std::vector<Source> World::sources() const {
  std::vector<Source> out;
  for (const Emitter& e : supply_.emitters) out.push_back(e.src);
  return out;
}

size_t World::addSource(const Source& s) {
  supply_.emitters.push_back(makeEmitter(s, params_, "source"));
  return supply_.emitters.size() - 1;
}

void World::updateSource(size_t i, const Source& s) {
  require(i < supply_.emitters.size(), "source " + std::to_string(i) + " does not exist");
  Emitter next = makeEmitter(s, params_, "source");
  const long emitted = supply_.emitters[i].emitted, blocked = supply_.emitters[i].blocked;
  supply_.emitters[i] = std::move(next);
  supply_.emitters[i].emitted = emitted, supply_.emitters[i].blocked = blocked;
}

void World::removeSource(size_t i) {
  require(i < supply_.emitters.size(), "source " + std::to_string(i) + " does not exist");
  supply_.emitters.erase(supply_.emitters.begin() + long(i));
}

size_t World::addSink(const Sink& s) {
  require(s.lo.allFinite() && s.hi.allFinite() && (s.hi - s.lo).minCoeff() > 0,
          "sink: max must exceed min on every axis");
  supply_.sinks.push_back(s);
  return supply_.sinks.size() - 1;
}

void World::updateSink(size_t i, const Sink& s) {
  require(i < supply_.sinks.size(), "sink " + std::to_string(i) + " does not exist");
  require(s.lo.allFinite() && s.hi.allFinite() && (s.hi - s.lo).minCoeff() > 0,
          "sink: max must exceed min on every axis");
  supply_.sinks[i] = s;
}

void World::removeSink(size_t i) {
  require(i < supply_.sinks.size(), "sink " + std::to_string(i) + " does not exist");
  supply_.sinks.erase(supply_.sinks.begin() + long(i));
}

long World::addWater(const Eigen::Vector3d& centre, double radius) {
  require(centre.allFinite() && std::isfinite(radius) && radius > 0, "water brush: needs a finite centre and radius > 0");
  const double ds = params_.spacing;
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
        if (x.x() < terrain_.x0() || x.x() > terrain_.xMax() || x.z() < terrain_.z0() || x.z() > terrain_.zMax()) continue;
        if (x.y() < terrain_.heightAt(x.x(), x.z()) + 0.5 * ds) continue;
        added += place(x.cast<float>(), Vec3f::Zero(), 0.95);  // water at rest: a full Δs apart
      }
  ledger_.painted += added;  // the brush is not a source: counted apart
  return added;
}

long World::blockedSlots() const {
  long s = 0;
  for (const auto& e : supply_.emitters) s += e.blocked;
  return s;
}

}  // namespace scour
