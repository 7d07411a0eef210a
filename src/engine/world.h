#pragma once
// World: the whole simulation state and the step that advances it.
//
// Threading contract: a World is touched by one thread at a time (the worker that owns it). Inside
// step(), passes run OpenMP loops; when step() returns, no parallel work is running. Every loop
// gathers into its own particle (no scatter, no float atomics) and every reduction that is not a
// min/max runs in a fixed order, so the state after N steps is bit-identical at any thread count.
//
// The step (model.md §7, leapfrog kick–drift–kick, velocities at half steps):
//   choose Δt → kick ½Δt, drift → sinks / outflow → sources → [reorder along Z] → neighbor search →
//   boundary particles of the tiles near water → density, pressure → forces → boundary forces →
//   no-slip → kick ½Δt → invariants.
// With fluid.solver = dfsph (dfsph.h, symplectic Euler): choose Δt → v += Δt a_np → density solve →
//   drift → sinks, sources → neighbor search → sediment, erosion, terrain → density, α →
//   divergence solve → a_np (viscosity, cohesion, gravity, the walls' hydrostatic term,
//   no-slip) → invariants.
// Passes that the scene does not call for (no sources, no friction, …) are not run at all.

#include <array>
#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/boundary.h"
#include "engine/dfsph.h"
#include "engine/flow_record.h"
#include "engine/fluid.h"
#include "engine/heightfield.h"
#include "engine/neighbors.h"
#include "engine/params.h"
#include "engine/sediment.h"
#include "engine/sources.h"
#include "engine/sph.h"

namespace scour {

enum class Pass {
  kNeighborSearch,
  kDensity,
  kForces,
  kBoundaryForces,
  kIntegrate,
  kSources,
  kSinks,
  kRain,
  kBoundaryParticles,
  kBoundaryNeighbors,
  kNoSlip,
  kSediment,
  kErosion,
  kTerrain,
  kFlowMaps,
  kInvariants,
  kPressureSolve,    ///< DFSPH's density solve
  kDivergenceSolve,  ///< DFSPH's divergence solve
  kCount
};
const char* passName(Pass p);

/// The paper's Table 1 columns a pass belongs to.
enum class Table1Group { kSph, kErosion, kBoundary, kOther };
Table1Group table1Group(Pass p);

/// Effects a scene calls for; a pass whose effect is off is not in the pass list.
struct Effects {
  bool fluid_motion = true;  ///< off: particles stay where they are (sediment-only scenes)
  bool surface_tension = false;
  bool no_slip = false;
  bool settling = false;    ///< eqs. (16)–(17)
  bool diffusion = false;   ///< eq. (19)
  bool deposition = false;  ///< eq. (20)
  bool erosion = false;     ///< eqs. (9)–(10)
  bool sources = true;      ///< the scene's sources emit
  bool sinks = true;        ///< the scene's sinks (and open walls) remove
  bool rain = true;         ///< the scene's rain falls
};

/// The soil budget [m³]: terrain above the initial lowest height, sediment suspended in the
/// fluid, sediment carried out by sinks and open walls, less the sediment a non-conservative
/// numerical form made (the naive advection, sediment.advection = naive_gradient; 0 otherwise).
struct SoilBudget {
  double terrain = 0, suspended = 0, removed = 0, initial = 0, created = 0;
  /// What the morphological factor added to the terrain beyond the water's exchange, Σ (N − 1) ×
  /// the net deposit of each step (negative where it eroded) [m³]; 0 at N = 1.
  double morphological = 0;
  double total() const { return terrain + suspended + removed - created - morphological; }
  double relativeError() const { return initial != 0 ? std::abs(total() - initial) / initial : 0; }
};

struct InvariantReport {
  long nan = 0;                          ///< non-finite values seen
  double max_penetration_over_ds = 0.0;  ///< deepest particle below the terrain, in Δs
  long escaped = 0;                      ///< particles found beyond a closed wall
  double c_min = 0.0, c_max = 0.0;       ///< extreme sediment concentrations seen
  double soil_relative_error = 0.0;      ///< worst |budget − initial| / initial over the steps
};

class InvariantViolation : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A run that reaches a limit of engine/limits.h while it runs (sources that have filled the
/// memory the limits allow): it stops as a violated invariant does, with the numbers.
class LimitExceeded : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What a World has counted since it began: particles placed and removed, the soil removed, the
/// energy given, what a non-conservative form made, the worst invariant values. It saves and
/// loads itself with the world state (world_state.cpp), all but `initialSoil` (the World's
/// construction sets it) and `energy` (counted again from a loaded state).
struct Ledger {
  long removedBySinks = 0, removedByOutflow = 0;
  long emitted = 0;  ///< by sources and rain
  long painted = 0;  ///< by the brush
  double removedSediment = 0;  ///< carried out by sinks and open walls [m³]
  double initialSoil = 0;      ///< the soil budget's total at the start [m³]
  double energy = 0;           ///< the mechanical energy given to the fluid [J] (energyLedger)
  SedimentDefects defects;
  InvariantReport invariants;
  /// Particles put back onto the terrain's wall surface after the drift carried them through it
  /// (World::step): impacts faster than the penalty holds.
  long terrainContacts = 0;
  /// SoilBudget::morphological: Σ (N v − v) over the boundary particles' net exchanges [m³].
  double morphological = 0;
  /// The bed-change guard's record: how often it lowered the factor, the lowest it set, and the
  /// hydraulic time of the last time.
  struct BedGuard {
    long lowered = 0;
    double lowest = 0, lastAt = 0, lastFrom = 0;  ///< lastFrom: the factor before the last
  } guard;

  void save(std::ostream& out) const;
  /// `version`: of the world state being read (defects from version 2 on).
  void load(std::istream& in, uint32_t version);
};

/// The World's particle supply: the sources (with their progress), sinks and rain, the id the
/// next particle gets, and the room the memory limit leaves. It saves and loads its progress
/// with the world state (world_state.cpp; the next id is saved with the clock).
struct Supply {
  std::vector<Emitter> emitters;
  std::vector<Sink> sinks;
  std::vector<RainState> rain;
  uint32_t nextId = 0;
  size_t maxParticles = 0;  ///< particles the memory limit leaves room for (engine/limits.h)

  void saveProgress(std::ostream& out) const;
  /// Throws std::runtime_error, changing nothing, when the state's sources or rain are not these.
  void loadProgress(std::istream& in);
};

struct StepStats {
  double dt = 0, time = 0, max_speed = 0;
  size_t particles = 0;
  long step = 0;
  /// The geologic clock: the bed's time ∫ N dt [s], the factor this step used (1 in the
  /// spin-up), and how fast the bed moved: the largest change a boundary particle's bed made
  /// [Δs], and the share of the exchanging bed (by area) that moved at least a tenth of the
  /// guard's bound [-].
  double morph_time = 0, factor = 1, bed_step_ds = 0, bed_fast_fraction = 0;
  /// DFSPH (fluid.solver = dfsph): the iterations of the step's density and divergence solves and
  /// the mean errors they ended at (relative, as fluid.max_density_error); 0 under WCSPH.
  int density_iterations = 0, divergence_iterations = 0;
  double density_error = 0, divergence_error = 0;
};

struct WorldDesc {
  SimParams params;
  Heightfield terrain;
  Domain domain;
  Effects effects;
  std::vector<Eigen::Vector3f> particles;  ///< initial positions (at rest)
  /// Initial pressure of each particle [Pa] (e.g. hydrostatic); empty = 0. Sets the initial
  /// continuity density through the inverse equation of state.
  std::vector<float> pressure;
  /// Initial sediment concentration C of each particle; empty = 0.
  std::vector<double> concentration;
  std::vector<Source> sources;
  std::vector<Sink> sinks;
  std::vector<Rain> rain;
};

class World {
 public:
  /// Validates the description (throws std::invalid_argument with the field named).
  explicit World(WorldDesc desc);

  StepStats step();

  // Live edits (the app's commands, applied between steps).
  /// New parameters from the next step on. Throws std::invalid_argument naming the field for an
  /// invalid set, or for a change of fluid.spacing, fluid.support_over_spacing,
  /// fluid.rest_density (they shape the particles) or engine.neighbor_search: those need a reset.
  void setParams(const SimParams& p);
  /// The sources as they are now.
  std::vector<Source> sources() const;
  /// Adds a source (validated as in the constructor); returns its index.
  size_t addSource(const Source& s);
  /// Changes a source's place, direction, radius, rate or times; its progress restarts.
  void updateSource(size_t i, const Source& s);
  void removeSource(size_t i);
  const std::vector<Sink>& sinks() const { return supply_.sinks; }
  size_t addSink(const Sink& s);
  /// Changes a sink's box (validated as in addSink); what it removed so far stays counted.
  void updateSink(size_t i, const Sink& s);
  void removeSink(size_t i);
  /// Fills the free lattice points of spacing Δs within `radius` of `centre` that lie at least
  /// Δs/2 above the terrain with water at rest (the brush). Returns how many particles it added.
  long addWater(const Eigen::Vector3d& centre, double radius);

  const SimParams& params() const { return params_; }
  const Heightfield& terrain() const { return terrain_; }
  const Fluid& fluid() const { return fluid_; }
  const BoundaryParticles& boundary() const { return boundary_; }
  const NeighborLists& neighbors() const { return neighbors_.fluid(); }
  const Domain& domain() const { return domain_; }
  double time() const { return time_; }
  /// The bed's clock, ∫ N dt over the steps (model.md, "two clocks") [s].
  double morphologicalTime() const { return morphTime_; }
  /// The morphological factor in effect: erosion.morphological_factor, or less where the bed
  /// guard lowered it (until the parameter is set again); the spin-up aside.
  double morphologicalFactor() const { return factor_; }
  /// The factor the next step uses: 1 in the spin-up, else morphologicalFactor().
  double factorNow() const { return time_ >= params_.morphological_spinup ? factor_ : 1.0; }
  const Ledger::BedGuard& bedGuard() const { return ledger_.guard; }
  /// The most the last step moved the bed anywhere, over Δs (StepStats::bed_step_ds).
  double lastBedStep() const { return bedStep_; }
  long steps() const { return step_; }
  double lastDt() const { return dt_; }

  /// Seconds spent in each pass, and how often it ran, since construction.
  const std::array<double, size_t(Pass::kCount)>& passSeconds() const { return passSeconds_; }
  const std::array<long, size_t(Pass::kCount)>& passCalls() const { return passCalls_; }
  const InvariantReport& invariants() const { return ledger_.invariants; }
  long removedBySinks() const { return ledger_.removedBySinks; }
  long removedByOutflow() const { return ledger_.removedByOutflow; }
  long emitted() const { return ledger_.emitted; }
  long painted() const { return ledger_.painted; }
  /// Particles the hard floor under the penalty put back onto the terrain (Ledger).
  long terrainContacts() const { return ledger_.terrainContacts; }
  long blockedSlots() const;
  /// Mechanical energy of the fluid now, Σ m (½|v|² + g y) [J].
  double mechanicalEnergy() const;
  /// The mechanical energy the fluid has been given: its value at construction plus that of every
  /// particle placed since (sources, rain, brush) minus that of every particle removed (sinks,
  /// open walls) [J]. Without dissipation mechanicalEnergy() would equal it; it may only fall
  /// below. Not part of saveState: after loadState it counts from the loaded state.
  double energyLedger() const { return ledger_.energy; }
  /// max |dρ/dt|/ρ of the last step (continuity density), which bounds the next Δt [1/s].
  double densityRate() const { return densityRate_; }
  /// DFSPH: the last step's density and divergence solves (zero under WCSPH).
  const SolveReport& densitySolve() const { return densitySolve_; }
  const SolveReport& divergenceSolve() const { return divergenceSolve_; }

  /// A budget further than this from its initial value stops the run (relative).
  static constexpr double kSoilTolerance = 1e-6;
  /// The soil budget now (the terrain part is summed over every vertex, and counts the volume
  /// waiting for its triangle).
  SoilBudget soilBudget() const;
  /// Volume exchanged with the terrain but not yet in its heights (below
  /// kTerrainApplyOverSpacing on its triangle), + deposited [m³].
  double terrainWaiting() const { return accumulator_.waitingVolume(); }
  /// The terrain with the waiting volumes settled onto their triangles (as they will be once they
  /// reach the threshold): what every output shows, so a picture, an export or a height change
  /// holds all the soil exchanged so far. The world's own terrain() lags it by at most
  /// kTerrainApplyOverSpacing Δs per triangle.
  Heightfield settledTerrain() const;
  /// Height change of every vertex since the start, of settledTerrain() [m].
  std::vector<double> heightChange() const;
  const Heightfield& initialTerrain() const { return initialTerrain_; }
  /// Each vertex's share of the terrain's area, A_v (vertexAreas) [m²].
  const std::vector<double>& vertexArea() const { return vertexArea_; }
  /// The flow, wetness and shear recorded over the run (flow_record.h; empty while neither
  /// erosion nor deposition is on).
  const FlowRecord& flowRecord() const { return flow_; }
  /// What the naive advection (sediment.advection = naive_gradient) made or destroyed since the
  /// start, and the extreme C before the clamp (from the initial range on). With the conservative
  /// forms the volumes stay 0 and the C range is the initial one.
  const SedimentDefects& sedimentDefects() const { return ledger_.defects; }
  /// Sediment concentration C of particle i.
  double concentration(size_t i) const { return fluid_.sed[i] / sediment_.volume; }

  /// FNV-1a over particle count, positions, velocities, sediment, heights and time, the volumes
  /// waiting for their triangles and the bed's clock (its time and the factor in effect).
  uint64_t stateHash() const;
  /// Everything a later step reads that the description does not determine: particles, terrain,
  /// boundary particles and active tiles, source and rain progress, time, counters. A World
  /// made from the same description and given this state steps on bit for bit as the original.
  void saveState(std::ostream& out) const;
  /// Restores saveState's output. Throws std::runtime_error when it does not fit this World.
  void loadState(std::istream& in);
  /// Bytes held by particle arrays, grid and neighbor lists.
  size_t memoryBytes() const;

 private:
  template <class F>
  void timed(Pass pass, F&& f);
  double chooseDt() const;
  void searchNeighbors();
  /// The fluid–fluid lists (grid or kd-tree, as params_.neighbor_search says).
  void buildFluidLists();
  /// The fluid–boundary lists, after buildFluidLists.
  void buildBoundaryLists();
  void computeAccelerations();
  /// DFSPH after a neighbor search: density and α, the divergence solve (not before the first
  /// step), then the non-pressure accelerations.
  void implicitAccelerations(bool divergence);
  bool implicit() const { return params_.solver == FluidSolver::kDfsph; }
  void removeParticles();
  void emit();
  void rain();
  /// A source's new particle needs this much room (in Δs): its layer comes Δs after the last
  /// one, so less room means the water ahead is held up (a jet into a wall) and a new particle
  /// would be squeezed into it.
  static constexpr double kEmitClearance = 0.8;
  /// Distance from a closed wall within which no particle is placed: Δs/2 (where a lattice's
  /// first layer sits), or the contact distance if larger [m].
  double wallMargin() const { return params_.spacing * std::max(0.5, params_.contact_over_spacing); }
  /// The part of a rain's rectangle over the terrain [m²].
  double rainArea(const Rain& r) const;
  /// Sets the simulation box: the terrain's rectangle and height range, grown on every side by
  /// its larger extent, and upwards by the height a particle at the sound speed could climb. A
  /// particle outside it has been flung out by a blow-up (checkInvariants).
  void simulationBox();
  Vec3f boxLo_ = Vec3f::Zero(), boxHi_ = Vec3f::Zero();
  /// Places a particle unless one lies closer than clearance·Δs, or a closed wall closer than
  /// wallMargin(); returns whether it did. Throws LimitExceeded at the particle limit.
  bool place(const Vec3f& pos, const Vec3f& vel, double clearance = 0.5);
  void checkInvariants();
  /// The sediment exchange, erosion and the terrain's update over `span` seconds of water.
  void sedimentWork(double span);
  bool needsBoundary() const { return effects_.no_slip || effects_.erosion || effects_.deposition; }

  SimParams params_;
  SphConstants sph_;
  DfsphConstants dfsphK_;  ///< the implicit solver's kernel and wall tables
  SedimentConstants sediment_;
  Heightfield terrain_, initialTerrain_;
  WallSurface wall_;  // what the walls see of terrain_
  std::vector<double> vertexArea_;
  double terrainReference_ = 0;
  TerrainAccumulator accumulator_;
  SedimentWorkspace sedimentWork_;
  FlowRecord flow_;
  Domain domain_;
  Effects effects_;
  Fluid fluid_;
  std::vector<Vec3f> vhat_;
  Supply supply_;
  Neighborhood neighbors_;
  BoundarySampler sampler_;
  BoundaryParticles boundary_;
  double time_ = 0, dt_ = 0;
  long step_ = 0;
  double morphTime_ = 0;  ///< ∫ N dt [s]
  double factor_ = 1;     ///< the factor in effect (the guard may lower it)
  double stepFactor_ = 1;  ///< the factor of the step under way
  /// The last terrain pass's bed motion (StepStats), over Δs and as a share of the area.
  double bedStep_ = 0, bedFast_ = 0;
  Ledger ledger_;
  /// max |dρ/dt|/ρ of the last continuity step [1/s]; 0 = none yet.
  double densityRate_ = 0;
  DfsphWorkspace dfsph_;
  SolveReport densitySolve_, divergenceSolve_;
  /// m (½|v|² + g y) of particle i [J].
  double particleEnergy(size_t i) const;
  std::array<double, size_t(Pass::kCount)> passSeconds_{};
  std::array<long, size_t(Pass::kCount)> passCalls_{};
};

}  // namespace scour
