#pragma once
// Erosion, sediment transport and deposition (paper §4, model.md §3–6).
//
// Each fluid particle carries a sediment volume s_i [m³]; its concentration is C_i = s_i / V with
// V = m/ρ0 the particle's rest volume (constant, so the budget does not breathe with the weakly
// compressible density). All exchanges are pairwise *volume* fluxes, evaluated by one function
// from the same operands on both sides of a pair, so what one particle gives the other receives
// to the bit, and the soil budget (terrain + suspended + removed) closes to rounding.
//
// One step of sediment work:
//  1. transferSediment: donor–acceptor settling along v_s (eqs. 16–17, flux doubled per
//     model.md), diffusion (model.md's consistent eq. 19) and deposition onto the boundary
//     particles below (eq. 20). The paper's two steps: sum each particle's raw outflow and
//     inflow, then apply every directed flux scaled by min(donor's factor, acceptor's factor),
//     the factors chosen so no donor gives more than it holds and no acceptor passes C_max. The
//     first pass applies the fluxes unscaled as it sums, so the second runs only when a factor
//     is below 1.
//  2. erode: shear stress τ = K θⁿ, θ = |v_j| / l, Partheniades ε = K_ε(τ − τ_c) (eqs. 9–10),
//     each pair's mass L_b² ε Δt taken from the boundary particle into the fluid particle, capped
//     so that C_j ≤ C_max.
//  3. applyTerrainChange: per-triangle volumes (eq. 21) to vertex heights (eq. 22) with slippage.
// Accuracy-study options (SimParams::advection, diffusion_form): the naive advection −v_s·∇C is a
// per-particle rate of C, not a pairwise flux, so it makes or destroys sediment; C is clamped into
// [0, C_max] after it and what it made is counted (SedimentDefects) so the soil budget still
// closes. The printed diffusion of eq. (19) keeps the pairwise form with its own coefficient.
// Fluid-side updates are parallel gathers; the per-triangle sums are accumulated serially in
// particle order, so the result is the same at any thread count.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/boundary.h"
#include "engine/fluid.h"
#include "engine/heightfield.h"
#include "engine/kernels.h"
#include "engine/neighbors.h"
#include "engine/params.h"

namespace scour {

struct SedimentEffects {
  bool settling = false, diffusion = false, deposition = false, erosion = false;
  bool any() const { return settling || diffusion || deposition || erosion; }
};

/// Constants of the sediment passes, from SimParams.
struct SedimentConstants {
  explicit SedimentConstants(const SimParams& p);
  double volume;      ///< V = m/ρ0 [m³]
  /// 1/Δs²: a boundary particle's share of eq. (20) is L_b²/Δs² of a fluid-spacing one's [1/m²].
  double per_area;
  double c_max, rz, vs0, diffusion, k_eps, tau_c, shear_k, shear_n, rho_s;
  double mass;          ///< m, fluid particle mass (the printed eq. 19) [kg]
  SettlingAdvection advection;  ///< SimParams::advection
  DiffusionForm diffusion_form;  ///< SimParams::diffusion_form
  double min_distance;  ///< l is clamped below at this [m]
  CubicSpline spline;
  /// Richardson–Zaki f(C) = 1 − (C/C_max)^e, 0 for C ≥ C_max.
  double hindrance(double c) const;
  /// The same from a table (linear interpolation, error < 1e-6): one per particle and step.
  float hindranceFast(double c) const;
  std::vector<float> hindranceTable;
};

/// A triangle's exchanged volume goes into its heights once it would move them by at least this
/// many Δs on average (model.md, "the terrain takes its change in steps of 10⁻⁴ Δs"); until then
/// it waits in the accumulator, and the soil budget counts it as terrain.
constexpr double kTerrainApplyOverSpacing = 1e-4;

/// Volume exchanged with the terrain: + deposited, − eroded [m³]. A step's exchanges are summed
/// per boundary particle (addParticle), then moved to the terrain (spread): a particle that stands
/// for part of a triangle adds its sum to that triangle; one that stands for a block of cells adds
/// it to the block's bank, kept whole in its first triangle (the block's head), and the bank is
/// split over the block's triangles (in equal parts: their projected areas are equal) only when
/// applyTerrainChange applies it. A triangle's sum, or a bank, waits until it would move the
/// terrain by the threshold on average (model.md, "the terrain takes its change in steps of
/// 10⁻⁴ Δs"); the soil budget counts what waits as terrain.
struct TerrainAccumulator {
  /// What `code` says of a triangle: not listed, listed with its own sum, listed with a sum that
  /// applyTerrainChange applies this call whatever its size (a bank just split); any other value
  /// is the extent of a block (BoundaryParticles::extent, at least 1 × 1: 0x11) whose bank this
  /// triangle, its head, holds.
  static constexpr uint8_t kNone = 0, kTriangle = 1, kApplyNow = 2;
  static bool isHead(uint8_t code) { return code > kApplyNow; }

  std::vector<double> volume;   ///< per triangle: its sum, or its block's bank; not yet applied
  /// Triangles with an entry: those left waiting by the last applyTerrainChange in ascending
  /// order, then the ones touched since, in first-touch order. Each once.
  std::vector<int> touched;
  std::vector<uint8_t> code;    ///< per triangle: kNone, kTriangle, kApplyNow or a head's extent
  int cellsX = 0;               ///< the terrain's cells along x (a bank's triangles)
  std::vector<double> particle;     ///< per boundary particle: this step's exchange
  std::vector<uint8_t> particleListed;  ///< per boundary particle: 1 when in `particles`
  std::vector<uint32_t> particles;  ///< boundary particles with an entry, in first-touch order, each once
  /// Per vertex: == epoch when applyTerrainChange changed its height this step.
  std::vector<uint32_t> vertexMark;
  uint32_t epoch = 0;
  /// applyTerrainChange's scratch (the touched triangles by cell row, each row's start and fill),
  /// kept for its memory.
  std::vector<int> rowStart, byRow, rowNext, changedAt, waiting;
  void resize(int triangles, size_t vertices, int cellsAlongX = 0) {
    volume.assign(size_t(triangles), 0.0), code.assign(size_t(triangles), kNone);
    touched.clear(), particle.clear(), particleListed.clear(), particles.clear();
    vertexMark.assign(vertices, 0u), epoch = 0, cellsX = cellsAlongX;
  }
  /// Adds v to triangle tri's own sum; a bank it heads is split over its block first.
  void add(int tri, double v, uint8_t as = kTriangle) {
    uint8_t& c = code[size_t(tri)];
    if (isHead(c)) split(tri, kTriangle);
    if (c == kNone) touched.push_back(tri);
    if (c != kApplyNow) c = as;
    volume[size_t(tri)] += v;
  }
  /// Adds v to the bank of the block of `extent` (x: low 4 bits, z: high 4 bits) cells from cell
  /// `cell`. When its head already holds another sum (its own, or another block's bank: the
  /// terrain was sampled in other blocks since), v is split over the block's triangles instead.
  void addBlock(int cell, uint8_t extent, double v) {
    const int head = 2 * cell;
    uint8_t& c = code[size_t(head)];
    if (c == kNone) c = extent, touched.push_back(head);
    if (c == extent) {
      volume[size_t(head)] += v;
      return;
    }
    forEachBlockTriangle(cell, extent, v, [&](int tri, double part) { add(tri, part); });
  }
  /// Calls f(triangle, part) for each triangle of the block, row by row, part = v / triangles.
  template <class F>
  void forEachBlockTriangle(int cell, uint8_t extent, double v, F&& f) const {
    const int bx = extent & 15, bz = extent >> 4;
    const double part = v / (2.0 * bx * bz);
    for (int k = 0; k < bz; ++k)
      for (int i = 0; i < bx; ++i) {
        const int at = cell + k * cellsX + i;
        f(2 * at, part), f(2 * at + 1, part);
      }
  }
  /// Moves the bank headed by `head` into its block's triangles as their own sums (`as`).
  void split(int head, uint8_t as) {
    const uint8_t extent = code[size_t(head)];
    const double v = volume[size_t(head)];
    code[size_t(head)] = kTriangle, volume[size_t(head)] = 0.0;  // still listed, now as a triangle
    forEachBlockTriangle(head / 2, extent, v, [&](int tri, double part) { add(tri, part, as); });
  }
  /// Calls f(triangle, volume) for what waits, in `touched` order, a bank split by area.
  template <class F>
  void forEachWaiting(F&& f) const {
    for (int t : touched) {
      if (isHead(code[size_t(t)])) forEachBlockTriangle(t / 2, code[size_t(t)], volume[size_t(t)], f);
      else f(t, volume[size_t(t)]);
    }
  }
  /// Adds v to boundary particle j's sum for this step (`particle` grows to hold j).
  void addParticle(uint32_t j, double v) {
    if (j >= particle.size()) growParticles(j);
    if (!particleListed[j]) particleListed[j] = 1, particles.push_back(j);
    particle[j] += v;
  }
  /// Makes `particle` and `particleListed` hold boundary particle j (sediment.cpp: out of line,
  /// the rare path of addParticle).
  void growParticles(uint32_t j);
  /// Moves each boundary particle's sum, times the morphological factor, to its triangle or its
  /// block's bank, in first-touch order, and clears the sums. Adds to `excess` what the factor
  /// added beyond the exchange, Σ (N v − v) [m³] (0 at N = 1).
  void spread(const BoundaryParticles& b, double factor, double& excess) {
    if (b.cellsX > 0) cellsX = b.cellsX;
    for (uint32_t j : particles) {
      const double v = particle[j];
      particle[j] = 0.0, particleListed[j] = 0;
      if (v == 0.0) continue;
      const double bed = v * factor;
      excess += bed - v;
      if (b.patch[j] >= 0) addBlock(b.patch[j], b.extent[j], bed);
      else add(b.triangle[j], bed);
    }
    particles.clear();
  }
  void spread(const BoundaryParticles& b) {
    double excess = 0.0;
    spread(b, 1.0, excess);
  }
  /// How fast the bed moves under this step's sums (before spread): the largest |v_j| / L_b² [m]
  /// and the area of the boundary particles whose |v_j| / L_b² is at least `fast` [m²] beside
  /// the area of all with an exchange [m²].
  struct BedMotion {
    double peak = 0.0, fastArea = 0.0, area = 0.0;
  };
  BedMotion bedMotion(const BoundaryParticles& b, double fast) const {
    BedMotion m;
    for (uint32_t j : particles) {
      if (particle[j] == 0.0) continue;
      const double dh = std::abs(particle[j]) / b.area[j];
      m.peak = std::max(m.peak, dh);
      m.area += b.area[j];
      if (dh >= fast) m.fastArea += b.area[j];
    }
    return m;
  }
  /// The volume waiting in the triangles, summed in `touched` order [m³].
  double waitingVolume() const {
    double s = 0.0;
    for (int t : touched) s += volume[size_t(t)];
    return s;
  }
  /// Whether vertex v (k·nx + i) moved in the last applyTerrainChange.
  bool moved(int v) const { return vertexMark[size_t(v)] == epoch; }
};

/// What a non-conservative form did to the sediment (only the naive advection makes these
/// non-zero; the conservative forms leave them at 0).
struct SedimentDefects {
  double created = 0;    ///< net sediment volume made (+) or destroyed (−) [m³]
  double clipped = 0;    ///< of which by clamping C into [0, C_max] (+ where C went below 0) [m³]
  double c_min_raw = 0;  ///< lowest C before the clamp [-]
  double c_max_raw = 0;  ///< highest C before the clamp [-]
};

/// Per-step scratch of transferSediment, kept between steps so its memory is reused.
struct SedimentWorkspace {
  struct Scales {
    double out = 1, in = 1;  ///< the donor's and the acceptor's factor
  };
  std::vector<float> conc, hind;
  std::vector<Scales> scale;
  std::vector<double> delta;
  /// erode's (or bedShear's) bed shear stress per particle [Pa], −1 with no boundary neighbor.
  std::vector<float> tau;
  /// Per thread, the (boundary particle, volume) exchanges of its block of fluid particles, in
  /// particle order (deposition, then erosion); kept so their memory is reused.
  std::vector<std::vector<std::pair<uint32_t, double>>> exchanges;
  /// The last call's defects (naive advection only; zero otherwise).
  SedimentDefects defects;
};

/// Step 1 (fluid–fluid and fluid–boundary transfer) of the sediment work; adds deposits to the
/// boundary particles' sums in acc.
void transferSediment(const SedimentConstants& k, const SedimentEffects& fx,
                      const NeighborLists& nbrs, const NeighborLists& bnbrs,
                      const BoundaryParticles& b, double dt, Fluid& f, TerrainAccumulator& acc,
                      SedimentWorkspace& ws);

/// Each particle's bed shear stress, the largest of eq. (9) over its boundary neighbors [Pa], −1
/// for a particle with none (erode fills the same into its workspace's tau).
void bedShear(const SedimentConstants& k, const NeighborLists& bnbrs, const BoundaryParticles& b,
              const Fluid& f, std::vector<float>& tau);

/// Step 2: erosion by shear stress; subtracts eroded volumes from the boundary particles' sums.
void erode(const SedimentConstants& k, const NeighborLists& bnbrs, const BoundaryParticles& b,
           double dt, Fluid& f, TerrainAccumulator& acc, SedimentWorkspace& ws);
inline void erode(const SedimentConstants& k, const NeighborLists& bnbrs, const BoundaryParticles& b,
                  double dt, Fluid& f, TerrainAccumulator& acc) {
  SedimentWorkspace ws;
  erode(k, bnbrs, b, dt, f, acc, ws);
}

/// Per-vertex area weights of the soil volume: A_v = Σ_{t ∋ v} A_t / 3 (projected areas), so that
/// Σ_v h_v A_v is exactly the volume under the piecewise-linear surface.
std::vector<double> vertexAreas(const Heightfield& hf);

/// A terrain's change against its start: the deepest cut and the highest deposit [m], and the
/// volumes cut and deposited, Σ_v max(0, ∓Δh_v) A_v in vertex order [m³].
struct TerrainChange {
  double max_erosion = 0, max_deposition = 0, eroded = 0, deposited = 0;
};
TerrainChange measureTerrainChange(const std::vector<double>& dh, const std::vector<double>& areas);

/// Soil volume above `reference`: Σ_v (h_v − reference) A_v, summed in vertex order.
double terrainVolume(const Heightfield& hf, const std::vector<double>& areas, double reference);

/// Adds volume V to triangle `tri` (V < 0 removes): deposition fills the lowest vertex first until
/// level with the next, then the two, then raises all three; erosion cuts the highest first.
/// Σ Δh_v A_v = V to rounding.
void depositOnTriangle(Heightfield& hf, const std::vector<double>& areas, int tri, double volume);

/// Step 3: applies the triangles whose volume would move them by at least `threshold` [m] on
/// average (|V| ≥ threshold · A_t; 0 applies every one) and clears them, and so the banks whose
/// volume would move their block by that much (split into the block's triangles first); the
/// others stay, in ascending order, at the front of acc.touched. The triangles of one cell row go in ascending
/// order; the rows run in two rounds, the even rows then the odd ones, each round in parallel
/// (two rows of a round share no vertex), so the result is the same at any thread count. Marks
/// the vertices whose height changed (acc.moved) and returns them, each once, in an order that
/// depends on the touched triangles alone. Call acc.spread first: the boundary particles' sums
/// are not read here.
std::vector<int> applyTerrainChange(Heightfield& hf, const std::vector<double>& areas,
                                    TerrainAccumulator& acc, double threshold = 0.0);

}  // namespace scour
