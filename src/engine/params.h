#pragma once
// SimParams: every number the engine reads, as an aggregate with defaults. Units are SI.
// The one parameter table (kParams) names each field once, with label, unit, range, group and the
// paper's symbol; the scene reader, the CLI --set overrides and (later) the GUI are all built from
// it, so no code lists the fields one by one.

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace scour {

// The choice parameters: stored as these enums, read and written by the names in the parameter
// table (in the order of the enumerators).
enum class EquationOfState { kTait, kIdealGas };                  // fluid.eos: tait, ideal_gas
enum class DensityMethod { kContinuity, kSummation };             // fluid.density
enum class NeighborSearch { kGrid, kKdTree };                     // engine.neighbor_search
enum class BoundarySampling { kTriangles, kSpacing };             // engine.boundary_sampling
enum class SettlingAdvection { kDonorAcceptor, kNaiveGradient };  // sediment.advection
enum class DiffusionForm { kConsistent, kPrinted };               // sediment.diffusion_form
enum class FluidSolver { kWcsph, kDfsph };                        // fluid.solver

struct SimParams {
  // --- fluid (paper §3) ---
  /// Δs, particle spacing [m].
  double spacing = 0.02;
  /// h / Δs, kernel support radius over spacing (paper: h ≈ 2Δs) [-].
  double support_over_spacing = 2.0;
  /// ρ0, rest density of water [kg/m³].
  double rest_density = 1000.0;
  /// c_s, numerical speed of sound; should be ≥ 10 |v|max [m/s].
  double sound_speed = 20.0;
  /// Equation of state: Tait (default), or Müller's ideal gas p = k(ρ − ρ0), k = c_s².
  EquationOfState eos = EquationOfState::kTait;
  /// Density: the continuity equation with δ-SPH diffusion (default), or the kernel summation.
  DensityMethod density = DensityMethod::kContinuity;
  /// δ, δ-SPH density diffusion coefficient (continuity density only) [-].
  double density_diffusion = 0.1;
  /// ν, artificial kinematic viscosity for the viscosity-kernel Laplacian term [m²/s].
  double viscosity = 1e-3;
  /// κ, Becker–Teschner cohesion strength [m³/s²].
  double surface_tension = 0.0;
  /// g, gravitational acceleration along −y [m/s²].
  double gravity = 9.81;
  /// The pressure solver: weakly compressible SPH (the paper's, default) or divergence-free SPH
  /// (Bender & Koschier 2015/2017; docs/model.md, "the implicit solver").
  FluidSolver solver = FluidSolver::kWcsph;
  /// DFSPH: the density solve iterates until the mean compression, (ρ* − ρ0)/ρ0 over the
  /// particles, is at most this [-].
  double max_density_error = 0.001;
  /// DFSPH: the divergence solve iterates until the mean compression rate times Δt,
  /// Δt (Dρ/Dt)/ρ0, is at most this [-].
  double max_divergence_error = 0.001;
  /// DFSPH: the most iterations of each solve in one step [-].
  int max_iterations = 100;

  // --- time step (model.md §1) ---
  /// Upper bound on Δt (paper: 2 ms) [s].
  double max_dt = 0.002;
  /// λ, CFL factor in Δt = λ h / max(c_s, |v|max) [-].
  double cfl = 0.4;
  /// Factor in the force criterion Δt = λ_f √(h / |a|max) [-].
  double force_cfl = 0.25;
  /// λ_ρ in Δt ≤ λ_ρ / max |dρ/dt|/ρ over the last step: no particle's density may change by
  /// more than about this fraction in a step (continuity density only) [-].
  double density_cfl = 0.05;
  /// If > 0, Δt is fixed to this value (the paper's fixed-step policy) [s].
  double fixed_dt = 0.0;
  /// DFSPH's step: Δt ≤ λ_v h / |v|max, the velocity CFL (no sound speed) [-].
  double velocity_cfl = 0.25;
  /// DFSPH's upper bound on Δt; WCSPH's is time.max_dt [s].
  double implicit_max_dt = 0.005;

  // --- boundary (paper §3.1, eqs. 6–8) ---
  /// K_S, penalty stiffness per unit mass [1/s²]; 0 = derived from the scene's water depth.
  double penalty_stiffness = 0.0;
  /// K_D, penalty damping per unit mass [1/s]; 0 = critical damping for K_S.
  double penalty_damping = 0.0;
  /// Contact distance from the terrain and walls within which eq. (6) acts, over Δs [-].
  double contact_over_spacing = 0.5;
  /// μ_b, no-slip friction constant of eq. (8) [m³/s].
  double boundary_friction = 0.0;

  // --- erosion and sediment (paper §4, model.md §3–6) ---
  /// K_ε, erosion strength (Partheniades) [kg/(m²·s·Pa)].
  double k_eps = 0.1;
  /// τ_c, critical shear stress [Pa].
  double tau_c = 3.0;
  /// K, shear-stress constant of τ = K θⁿ [Pa·sⁿ].
  double shear_k = 1.0;
  /// n, flow behaviour index of τ = K θⁿ [-].
  double shear_n = 0.5;
  /// D, sediment diffusivity (kinematic, model.md's consistent form of eq. 19) [m²/s].
  double diffusion = 0.1;
  /// r_s, sediment grain radius [m].
  double grain_radius = 1e-3;
  /// ρ_s, sediment (soil) density [kg/m³].
  double sediment_density = 2650.0;
  /// C_max, maximum solid volume fraction of a fluid particle [-].
  double c_max = 0.6;
  /// e, Richardson–Zaki exponent of f(C) = 1 − (C/C_max)^e [-].
  double rz_exponent = 4.65;
  /// Settling advection: the donor–acceptor volume flux (eq. 16 doubled, model.md; default), or
  /// the naive −v_s·∇C with the symmetric-difference SPH gradient, per particle as a rate of C
  /// (not conservative; kept as the accuracy study's baseline).
  SettlingAdvection advection = SettlingAdvection::kDonorAcceptor;
  /// Diffusion: model.md's consistent form of eq. (19) (default), or eq. (19) as printed,
  /// Σ m/(ρ_i ρ_j) D (C_i − C_j) F (not dimensionally consistent; for the accuracy study).
  DiffusionForm diffusion_form = DiffusionForm::kConsistent;
  /// μ in eq. (17), "settling viscosity": Stokes' law with water's viscosity gives metres per
  /// second for 1 mm grains, out of its range; the default gives v_s ≈ 0.1 m/s [Pa·s].
  double settling_viscosity = 0.036;

  // --- the geologic clock (model.md, "two clocks") ---
  /// N, the morphological acceleration factor (Delft3D's MorFac): the bed changes by N times a
  /// step's net exchange with the water, so it runs in morphological time ∫ N dt; 1 is the bed
  /// in hydraulic time [-].
  double morphological_factor = 1.0;
  /// Hydraulic time before N acts (Delft3D's MorStt): the flow settles first [s].
  double morphological_spinup = 0.0;
  /// The bed-change guard: the most the bed may move anywhere in one step, over Δs. A step whose
  /// exchange times N would move it more halves N until it does not (never below 1) [-].
  double max_bed_step = 0.01;
  /// K: the sediment exchange, erosion, the terrain's update and the flow maps run every K-th
  /// step, over the K steps' time (model.md, "the bed's work every K steps"); 1 runs them every
  /// step, the model as before [-].
  int exchange_every = 1;

  // --- bookkeeping ---
  /// Steps between reorders of the particle arrays along the Z-order curve [-].
  int reorder_every = 16;
  /// Neighbor search: a uniform grid (default), or a kd-tree rebuilt every step (nanoflann; the
  /// paper's choice). Both find the same neighbor sets; the kd-tree lists are in ascending index.
  NeighborSearch neighbor_search = NeighborSearch::kGrid;
  /// Boundary particles: about one per Δs² on a terrain finer than Δs, each standing for a block
  /// of cells (default; docs/model.md, "boundary particles at the fluid's spacing"), or n² per
  /// terrain triangle (at least one, so a terrain finer than Δs carries several per Δs²).
  BoundarySampling boundary_sampling = BoundarySampling::kSpacing;
  /// A particle deeper than this below the terrain stops the run [Δs].
  double max_penetration_over_ds = 0.5;

  double support() const { return support_over_spacing * spacing; }
  /// m = ρ0 / Σ_lattice W_poly6: a particle resting on the cubic lattice of spacing Δs reads ρ0
  /// exactly (ρ0Δs³ would read 1 % more at h = 2Δs; see docs/model.md) [kg].
  double particleMass() const;
  /// Volume a fluid particle stands for in the sediment budget, m/ρ0 (constant, so that the
  /// budget does not breathe with the weakly compressible density) [m³].
  double particleVolume() const;
  /// |v_s| of eq. (17) for f(C) = 1 [m/s].
  double settlingSpeed() const {
    return 2.0 / 9.0 * grain_radius * grain_radius * (sediment_density - rest_density) /
           settling_viscosity * gravity;
  }
};

/// One row of the parameter table.
struct ParamInfo {
  const char* key;     ///< scene/CLI key, "group.name"
  const char* label;   ///< human label for the GUI
  const char* symbol;  ///< the paper's symbol, or ""
  const char* unit;
  double min, max;  ///< valid closed range
  const char* help;
  /// The window's slider spans [slider_min, slider_max] (within the valid range; 0, 0: the valid
  /// range), logarithmically when slider_min > 0 and the span is 100× or more. Values of the
  /// valid range outside it are typed (Ctrl+click).
  double slider_min = 0, slider_max = 0;
  double SimParams::*dmember = nullptr;
  int SimParams::*imember = nullptr;
  /// A choice (an enum field): the names of its values in enumerator order, nullptr-terminated,
  /// and the field read and written as the index into them.
  const char* const* choices = nullptr;
  int (*getChoice)(const SimParams&) = nullptr;
  void (*setChoice)(SimParams&, int) = nullptr;
};

const std::vector<ParamInfo>& paramTable();

/// What the window's slider of a number spans, and whether logarithmically.
struct SliderSpan {
  double lo, hi;
  bool log;
};
SliderSpan sliderSpan(const ParamInfo& i);

/// Looks up a key; nullptr if unknown.
const ParamInfo* findParam(std::string_view key);
/// Levenshtein distance, for "did you mean" suggestions.
size_t editDistance(std::string_view a, std::string_view b);
/// The name of `names` nearest `word` by edit distance, or "" if none is within `maxDistance`.
std::string nearestName(std::string_view word, const std::vector<std::string>& names,
                        size_t maxDistance = SIZE_MAX);
/// How far a word may be from a name and still be a slip of it: 2 edits, or a third of its length.
inline size_t slipDistance(std::string_view word) { return std::max<size_t>(2, word.size() / 3); }
/// The valid key closest to `key` by edit distance (for "did you mean" messages).
std::string nearestParamKey(std::string_view key);
/// Sets a parameter from text. Returns an empty string on success, else a message naming the key.
std::string setParam(SimParams& p, std::string_view key, std::string_view value);
double getParam(const SimParams& p, const ParamInfo& info);
/// Checks every field against its range; returns the first problem or "".
std::string validateParams(const SimParams& p);

}  // namespace scour
