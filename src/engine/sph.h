#pragma once
// The fluid passes of one step (paper §3), as free functions over the structure-of-arrays.
//
// Walls and terrain. The paper repels particles from the terrain with a penalty force only
// (eq. 6). Near a wall, though, the kernel sum misses the half-space beyond it, so particles there
// read a low density and the pressure that should hold the water up is missing; the penalty spring
// then carries the whole column and the hydrostatic profile is wrong near the bottom.
// **Decision:** every plane the particle is within h of (the terrain under it, treated locally as
// the plane of its triangle, and the domain's side walls) adds the missing part of the sums:
// density gains ρ0·Φ(d) and the pressure force gains the mirrored term 2·m·p_i/ρ_i²·G(d)·n, where
// Φ(d) is the share of the rest lattice's kernel sum that lies beyond a plane at distance d and
// G(d) the missing kernel-gradient sum. Both come from the same lattice the particles rest on, each
// layer counted by the share of its Δs-thick slab on the fluid side, so a particle resting on the
// lattice next to a wall reads ρ0 exactly and the bottom layer of a still column feels the
// hydrostatic push. Several planes combine as 1 − Π(1 − Φ_k). The eq. (6) penalty still acts
// within the contact distance, as in the paper.
//
// **Decision (mass):** m = ρ0 / Σ_lattice W_poly6 rather than ρ0Δs³: at h = 2Δs the lattice sum
// overestimates 1/Δs³ by about 1 %, which Tait's seventh power turns into a spurious pressure that
// blows the free surface apart at the first step.

#include <Eigen/Core>
#include <vector>

#include "engine/boundary.h"
#include "engine/fluid.h"
#include "engine/heightfield.h"
#include "engine/kernels.h"
#include "engine/neighbors.h"
#include "engine/params.h"

namespace scour {

/// The box the water lives in: the heightfield's x–z extent, closed by walls or open.
struct Domain {
  /// Side walls hold the water in; if false, particles that leave are removed and counted.
  bool walls = true;
};

/// Constants of one step, derived from SimParams once.
struct SphConstants {
  explicit SphConstants(const SimParams& p);
  double h, mass, rho0, c2, tait_b, delta;
  bool continuity;
  bool tait;
  float nu, kappa, gravity, ks, kd, contact, friction;
  Poly6 poly6;
  SpikyGrad spiky;
  ViscosityLaplacian visc;
  /// Φ(d): share of the rest-lattice density sum beyond a plane at signed distance d.
  double halfSpaceDensity(double d) const { return lookup(phi, d); }
  /// Equation of state (Tait or ideal gas), clamped at p ≥ 0 for free surfaces.
  double pressure(double rho) const;
  /// Inverse of the equation of state, for initial hydrostatic states.
  double densityFor(double pressure) const;
  /// A(d) = ∫ W_poly6 over a plane at distance |d| [1/m]: in the continuum, how fast the wall's
  /// share of the density grows as d shrinks (−dΦ/dd).
  double planeDensity(double d) const;
  /// The speed of sound at density ρ, √(dp/dρ): c_s for the linear law, c_s (ρ/ρ0)³ for Tait's
  /// above ρ0. The CFL step must follow it: a particle compressed to 1.45 ρ0 carries sound 3×
  /// faster than c_s, and a step sized for c_s lets its compression grow without bound.
  double soundSpeed(double rho) const {
    const double c = std::sqrt(c2);
    return tait && rho > rho0 ? c * std::pow(rho / rho0, 3.0) : c;
  }
  /// G(d): missing Σ_j |∇W_spiky|·(normal component) beyond the plane, per unit particle mass.
  double wallGradient(double d) const { return lookup(grad, d); }
  /// Missing share of Σ V x_ij x_ijᵀ |∇W|/r (= I in the interior) beyond the plane, along its
  /// normal and along a tangent.
  double momentNormal(double d) const { return lookup(momentN, d); }
  double momentTangential(double d) const { return lookup(momentT, d); }

 private:
  static constexpr int kTable = 1024;
  std::vector<double> phi, grad, momentN, momentT;  // over d ∈ [−h, h]
  double lookup(const std::vector<double>& t, double d) const;
  void buildWallTables(double spacing);
};

/// Calls f(n, d) for each plane within h of x: n the unit normal pointing into the fluid, d the
/// signed distance (negative = beyond the plane).
template <class F>
inline void forEachWall(const Heightfield& hf, const Domain& dom, double h, const Vec3f& x, F&& f) {
  SurfacePoint s = hf.surface(x.x(), x.z());
  double dt = (x.y() - s.height) * s.normal.y();
  // Over a steep triangle (a cliff's riser, narrower than h) the distance to its plane can be
  // far less than the distance to the triangle itself: a particle above the cliff's edge would
  // be pushed off it. Above the surface, the distance is to the triangle (`scour stress`, cliffs).
  if (dt > 0 && s.normal.y() < 0.5)
    dt = std::max(dt, hf.distanceToTriangle(s.triangle, x.cast<double>()));
  if (dt < h) f(s.normal, dt);
  if (!dom.walls) return;
  double d;
  if ((d = x.x() - hf.x0()) < h) f(Eigen::Vector3d(1, 0, 0), d);
  if ((d = hf.xMax() - x.x()) < h) f(Eigen::Vector3d(-1, 0, 0), d);
  if ((d = x.z() - hf.z0()) < h) f(Eigen::Vector3d(0, 0, 1), d);
  if ((d = hf.zMax() - x.z()) < h) f(Eigen::Vector3d(0, 0, -1), d);
}

/// ρ_i = Σ_j m W(r_ij) (self included) + wall terms; then p_i from the equation of state.
void computeDensity(const SphConstants& k, const NeighborLists& nbrs, const Heightfield& hf,
                    const Domain& dom, Fluid& f);

/// Continuity density (the default): dρ_i/dt = Σ_j m (v_i − v_j)·∇W_ij + δ-SPH diffusion + the
/// walls' share, integrated over dt with the drift velocity v; then p_i. Unlike the summation it
/// reads ρ0 at a free surface and does not drift with the particle arrangement, which is what
/// keeps a still column at hydrostatic pressure.
/// Returns the largest relative density rate max |dρ/dt|/ρ, for the next step's Δt.
double integrateDensity(const SphConstants& k, const NeighborLists& nbrs, const Heightfield& hf,
                        const Domain& dom, const std::vector<Vec3f>& v, double dt, Fluid& f);

/// Pressure, viscosity, surface tension and gravity: a_i. `vhat` is the velocity at the force
/// time (the leapfrog's predicted full-step velocity). Without `pressure` (DFSPH, whose solves
/// make the pressure), the rest.
void computeForces(const SphConstants& k, const NeighborLists& nbrs,
                   const std::vector<Vec3f>& vhat, Fluid& f, bool pressure = true);

/// Wall pressure (see above), its hydrostatic growth and the eq. (6) penalty; adds to a_i. Without
/// `pressure` (DFSPH, whose solves mirror the particle's own pressure), all but the mirrored term.
void applyBoundaryForces(const SphConstants& k, const Heightfield& hf, const Domain& dom,
                         const std::vector<Vec3f>& vhat, Fluid& f, bool pressure = true);

/// Eqs. (7)–(8), no-slip friction from the boundary particles within h; adds to a_i.
void applyNoSlip(const SphConstants& k, const NeighborLists& bnbrs, const BoundaryParticles& b,
                 const std::vector<Vec3f>& vhat, Fluid& f);

}  // namespace scour
