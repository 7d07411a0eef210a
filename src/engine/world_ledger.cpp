// The World's ledgers and invariants: the soil budget (terrain, suspended, removed), the
// mechanical energy given and held, and the checks that stop a step that breaks them.
#include "engine/world.h"
#include "engine/world_parts.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace scour {

double World::particleEnergy(size_t i) const {
  return sph_.mass * (0.5 * double(fluid_.v[i].squaredNorm()) + params_.gravity * double(fluid_.x[i].y()));
}

double World::mechanicalEnergy() const {
  double e = 0;  // a fixed-order sum, like every other reduction here
  for (size_t i = 0; i < fluid_.size(); ++i) e += particleEnergy(i);
  return e;
}

SoilBudget World::soilBudget() const {
  SoilBudget s;
  // The volume waiting in the accumulator for its triangles is terrain already.
  s.terrain = terrainVolume(terrain_, vertexArea_, terrainReference_) + accumulator_.waitingVolume();
  for (double v : fluid_.sed) s.suspended += v;
  s.removed = ledger_.removedSediment;
  s.initial = ledger_.initialSoil;
  s.created = ledger_.defects.created;
  s.morphological = ledger_.morphological;
  return s;
}

Heightfield World::settledTerrain() const {
  Heightfield hf = terrain_;
  accumulator_.forEachWaiting([&](int t, double v) { depositOnTriangle(hf, vertexArea_, t, v); });
  return hf;
}

std::vector<double> World::heightChange() const {
  const Heightfield now = settledTerrain();
  std::vector<double> d(now.heights().size());
  for (size_t i = 0; i < d.size(); ++i) d[i] = now.heights()[i] - initialTerrain_.heights()[i];
  return d;
}

void World::checkInvariants() {
  const size_t n = fluid_.size();
  const double ds = params_.spacing, slack = 0.5 * ds;
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
      const Vec3f& x = fluid_.x[i];
      if (!x.allFinite() || !fluid_.v[i].allFinite() || !fluid_.a[i].allFinite()) {
        upd(badNan, long(i));
        continue;
      }
      // Depth across the terrain (along its normal): the vertical one would call a particle
      // touching a near-vertical cliff face deep inside it. Below a steep triangle (a riser
      // narrower than a cell) its plane is no measure: the distance to the surface around.
      const SurfacePoint sp = terrain_.surface(x.x(), x.z());
      double depth = (sp.height - x.y()) * sp.normal.y() / ds;
      if (depth > 0 && sp.normal.y() < 0.5) depth = terrain_.distanceToSurface(x.cast<double>()) / ds;
      if (depth > tdeep || (depth == tdeep && long(i) < tat)) tdeep = depth, tat = long(i);
      if (domain_.walls && (x.x() < terrain_.x0() - slack || x.x() > terrain_.xMax() + slack ||
                         x.z() < terrain_.z0() - slack || x.z() > terrain_.zMax() + slack))
        upd(badOut, long(i));
      if ((x.array() < boxLo_.array()).any() || (x.array() > boxHi_.array()).any()) upd(badBox, long(i));
    }
#pragma omp critical(scour_inv_deep)
    if (tdeep > deepest || (tdeep == deepest && tat < deepestAt)) deepest = tdeep, deepestAt = tat;
  }
  ledger_.invariants.max_penetration_over_ds = std::max(ledger_.invariants.max_penetration_over_ds, std::max(deepest, 0.0));
  long badC = -1;
  for (size_t i = 0; i < n; ++i) {
    const double c = fluid_.sed[i] / sediment_.volume;
    ledger_.invariants.c_min = std::min(ledger_.invariants.c_min, c);
    ledger_.invariants.c_max = std::max(ledger_.invariants.c_max, c);
    if (badC < 0 && (c < -1e-12 || c > params_.c_max * (1 + 1e-12))) badC = long(i);
  }
  auto where = [&](long i) {
    std::ostringstream o;
    const Vec3f& x = fluid_.x[i];
    o << "step " << step_ << " (t = " << time_ << " s): particle " << i << " (id " << fluid_.id[i]
      << ") at (" << x.x() << ", " << x.y() << ", " << x.z() << ")";
    return o.str();
  };
  if (badNan >= 0) {
    ++ledger_.invariants.nan;
    const Vec3f& v = fluid_.v[badNan];
    std::ostringstream o;
    o << where(badNan) << " has a non-finite state: velocity (" << v.x() << ", " << v.y() << ", "
      << v.z() << ")";
    throw InvariantViolation(o.str());
  }
  if (badBox >= 0) {
    const Vec3f& v = fluid_.v[badBox];
    std::ostringstream o;
    o << where(badBox) << " left the simulation box (the terrain grown by its size on every side) "
      << "at speed " << v.norm() << " m/s: the run blew up";
    throw InvariantViolation(o.str());
  }
  // The soil budget, summed from scratch (every vertex, every particle) when soil can move.
  if (effects_.erosion || effects_.deposition || effects_.settling || effects_.diffusion) {
    const SoilBudget soil = soilBudget();
    const double err = soil.relativeError();
    ledger_.invariants.soil_relative_error = std::max(ledger_.invariants.soil_relative_error, err);
    if (!(err <= kSoilTolerance)) {
      std::ostringstream o;
      o << "step " << step_ << " (t = " << time_ << " s): the soil budget is off by " << err
        << " relative (terrain " << soil.terrain << " + suspended " << soil.suspended
        << " + removed " << soil.removed << " − what the geologic speed-up added "
        << soil.morphological << " m³ against " << soil.initial << " m³ at the start)";
      throw InvariantViolation(o.str());
    }
  }
  if (badC >= 0) {
    std::ostringstream o;
    o << where(badC) << " carries sediment concentration C = " << fluid_.sed[badC] / sediment_.volume
      << " outside [0, " << params_.c_max << "]";
    throw InvariantViolation(o.str());
  }
  if (badOut >= 0) {
    ++ledger_.invariants.escaped;
    throw InvariantViolation(where(badOut) + " has left the domain through a closed wall");
  }
  if (deepest > params_.max_penetration_over_ds) {
    std::ostringstream o;
    o << where(deepestAt) << " is " << deepest << " Δs below the terrain (limit "
      << params_.max_penetration_over_ds << " Δs)";
    throw InvariantViolation(o.str());
  }
}

}  // namespace scour
