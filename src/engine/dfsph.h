#pragma once
// Divergence-free SPH (Bender & Koschier, SCA 2015 and TVCG 2017), `fluid.solver = dfsph`: the
// pressure is not an equation of state of a compressed fluid but what makes the velocity field
// keep the density at ρ0 (the density solve, before the drift) and divergence free (the
// divergence solve, after the neighbor search). The step then follows the velocity, not the sound
// speed (docs/model.md, "the implicit solver").
//
// Kernel. The solves need the density and its gradient to be one function's: the density is the
// summation ρ_i = Σ_j m W_ij with Monaghan's cubic spline (support h), scaled so that the rest
// lattice reads ρ0 exactly, and every gradient in the solves is that kernel's. (WCSPH's poly6
// density with the spiky gradient is not a pair: a density solve on it does not converge to a
// still tank.)
//
// Notation: κ_i = p_i / ρ_i [m²/s²], so that the velocity change of a pressure κ over Δt is the
// symmetric SPH pressure force, Δv_i = −Δt (Σ_j m (κ_i/ρ_i + κ_j/ρ_j) ∇W_ij + 2 κ_i/ρ_i g_w,i): the
// walls mirror the particle's own κ, as WCSPH's wall pressure does. The factor
// α_i = ρ_i / (|G_i|² + Σ_j |m ∇W_ij|²), G_i = Σ_j m ∇W_ij + 2 g_w,i, turns a density error e into
// the κ that removes it when the neighbours' κ are alike: κ_i = e α_i / Δt².
//
// Walls and terrain (forEachWall's planes): a plane at distance d adds ρ0 Φ(d) to the density and
// g_w = ρ0 Φ'(d) n to its gradient, Φ fitted to the rest lattice (dfsph.cpp); several planes combine
// as 1 − Π(1 − Φ_k). They do not move. In the solves' linearised density a wall's share of Dρ_i/Dt
// counts twice, 2 v_i·g_w, as its push does: the force is then the constraint's gradient and the
// system symmetric (docs/model.md).
//
// Determinism: every sum over neighbours is one particle's, in its list's order; the mean errors
// are summed in fixed blocks of particles and then over the blocks in order, so the iteration
// counts and the state are the same at any thread count.

#include <vector>

#include "engine/fluid.h"
#include "engine/heightfield.h"
#include "engine/neighbors.h"
#include "engine/sph.h"

namespace scour {

/// The solves' kernel and the walls' tables, for one h, Δs and particle mass.
struct DfsphConstants {
  DfsphConstants(const SphConstants& k, double spacing);
  double h, mass, rho0;
  float hm, w0, f0;  ///< h/2; the scaled kernel's W and F = dW/dr coefficients
  /// Scaled cubic spline W(r) and (dW/dr)/r (0 at r = 0).
  float W(float r) const;
  float gradOverR(float r) const;
  /// Φ(d) and A(d) = −dΦ/dd for a plane at signed distance d (negative beyond it).
  double wallShare(double d) const { return lookup(phi_, d); }
  double wallRate(double d) const { return lookup(rate_, d); }

 private:
  static constexpr int kTable = 2048;
  std::vector<double> phi_, rate_;  // over d ∈ [−h, h]
  double lookup(const std::vector<double>& t, double d) const;
};

/// Per-particle values of one step (not state: recomputed from the positions after a load).
struct DfsphWorkspace {
  std::vector<float> alpha;   ///< α_i [m⁵/kg]
  std::vector<Vec3f> wall;    ///< the walls' share of ∇ρ_i, g_w [kg/m⁴]
  std::vector<float> change;  ///< κ change of the current iteration
  std::vector<float> error;   ///< the iteration's error per particle (for the ordered mean)
  /// m ∇W_ij of every pair of the fluid lists, in list order, computed once a step: the solves'
  /// passes over the pairs then need no square root or kernel. Particle i's start in it: first[i].
  std::vector<Vec3f> grad;
  std::vector<size_t> first;
  size_t bytes() const {
    return (alpha.capacity() + change.capacity() + error.capacity()) * sizeof(float) +
           (wall.capacity() + grad.capacity()) * sizeof(Vec3f) + first.capacity() * sizeof(size_t);
  }
};

/// What one solve did: its iterations and the mean error it ended at (relative, as the limits).
struct SolveReport {
  int iterations = 0;
  double error = 0;
};

/// The summation density ρ_i (into f.rho), α_i and the walls' share of ∇ρ_i, at the positions
/// the neighbor lists were built on.
void dfsphFactors(const DfsphConstants& k, const NeighborLists& nbrs, const Heightfield& hf, const Domain& dom,
                  Fluid& f, DfsphWorkspace& w);

/// The density solve: starts from half of the last step's κ = p/ρ where the water is compressed
/// (warm start), then corrects the velocities until the density predicted for x + Δt v has a mean
/// compression of at most `maxError` (at least 2 and at most `maxIterations` corrections), by a
/// projected Jacobi iteration: κ stays ≥ 0, and a particle that expands loses pressure. Leaves
/// p = κ ρ, the pressure that did it.
SolveReport solveDensity(const DfsphConstants& k, const NeighborLists& nbrs, double dt, double maxError,
                         int maxIterations, Fluid& f, DfsphWorkspace& w);

/// The divergence solve: corrects the velocities until the mean compression rate times Δt is at
/// most `maxError` (at least 1 correction). Only compression is corrected, and not where ρ_i < ρ0
/// (a free surface, where the kernel sum is short of neighbours).
SolveReport solveDivergence(const DfsphConstants& k, const NeighborLists& nbrs, double dt, double maxError,
                            int maxIterations, Fluid& f, DfsphWorkspace& w);

}  // namespace scour
