#pragma once
// What the water did over each terrain vertex during a run (issue 17, docs/exports.md): the
// near-bed flow, how long the vertex was wet, the bed shear stress. Accumulated every step while
// erosion or deposition is on, on the bed's (morphological) clock, and kept in the world state,
// so a checkpoint or a snapshot carries it and erosionMaps()' flow maps cover the whole run.
//
// A fluid particle is near the bed when it has a boundary neighbor (it lies within h of the
// terrain: the erosion's own neighborhood). Each near-bed particle i covers the vertices of the
// footprint square of side Δs centred under it (the nearest vertex when the grid is coarser than
// that), and in a step it gives each of them
//   q ⁺= V v_h,i / Σ_footprint A_v   [m²/s]   (so Σ_v q_v A_v = Σ_i V v_h,i: the near-bed water's
//                                              horizontal volume flux, shared by area),
//   τ = max(τ, τ_i),  τ_i = K (|v_i| / l_i)ⁿ  (eq. 9, l_i the distance to its nearest boundary
//                                              particle, clamped as erode clamps it) [Pa],
// and a vertex any particle covered is wet for that step. Over the run, with Δt_m = N Δt:
//   wet time    Σ Δt_m over its wet steps [s]
//   flow        Σ |q| Δt_m  [m³/m]: the near-bed water that passed over it, per unit width
//   direction   Σ q Δt_m    [m³/m], a vector (x, z)
//   shear       Σ τ Δt_m    [Pa s] and the peak τ [Pa]
// A vertex never covered keeps zeros in all of them. The per-vertex arrays live in tiles of
// 8 × 8 vertices made on first touch, so their memory follows the water (48 bytes a vertex: the
// six sums; a step's scratch is 16 bytes a particle and 4 for each tile a footprint covers).
// Each touched tile is summed by one thread, its particles in index order: the sums are the same,
// bit for bit, at any thread count.

#include <cstdint>
#include <vector>

#include "engine/fluid.h"
#include "engine/heightfield.h"

namespace scour {

class FlowRecord {
 public:
  static constexpr int kTile = 8;

  /// Starts an empty record over a grid of nx × nz vertices.
  void reset(int nx, int nz);
  /// Adds one step: tau[i] is particle i's bed shear stress, negative when it is not near the
  /// bed; dtm the step's bed time [s]; volume V and spacing Δs of a fluid particle [m³, m].
  void record(const Heightfield& hf, const std::vector<double>& vertexArea, const Fluid& f,
              const std::vector<float>& tau, double volume, double spacing, double dtm);

  double time() const { return time_; }  ///< bed time recorded [s]
  /// Per vertex over the whole grid (zeros where nothing was recorded), row-major.
  std::vector<double> wetTime() const { return dense(Field::kWet); }
  std::vector<double> flow() const { return dense(Field::kFlow); }
  std::vector<double> flowX() const { return dense(Field::kQx); }
  std::vector<double> flowZ() const { return dense(Field::kQz); }
  std::vector<double> shearIntegral() const { return dense(Field::kShear); }
  std::vector<double> shearPeak() const { return dense(Field::kPeak); }
  /// Tiles holding values (each once, in the order they were first touched).
  const std::vector<int>& tiles() const { return tiles_; }
  size_t bytes() const;

  /// The state: the bed time, the tiles and their values (the world state stores these).
  const std::vector<double>& values() const { return values_; }
  /// Puts back a state for a grid of nx × nz vertices, its tiles `tile` × `tile` vertices (a
  /// world state of version 7 has tiles of 16: they are cut into this build's, those holding
  /// nothing left out); std::runtime_error ("state is corrupt (flow maps)") when the tiles or
  /// values do not fit it. The record is unchanged then.
  void restore(int nx, int nz, double time, std::vector<int> tiles, std::vector<double> values,
               int tile = kTile);

 private:
  enum class Field { kWet, kFlow, kQx, kQz, kShear, kPeak, kCount };
  static constexpr int kFields = int(Field::kCount);
  std::vector<double> dense(Field f) const;
  /// The slot of a tile, made when absent.
  size_t slotOf(size_t tile);

  int nx_ = 0, nz_ = 0, tilesX_ = 0;
  double time_ = 0;
  std::vector<int32_t> slot_;   ///< per tile: its slot, or −1
  std::vector<int> tiles_;      ///< per slot: its tile
  std::vector<double> values_;  ///< per slot, kFields × kTile² values (field-major)
  /// This step's scratch: each particle's footprint (vertex ranges; empty when it is not near
  /// the bed), and the near-bed particles of each slot's tile in index order (member_ from
  /// start_[slot] to start_[slot + 1]).
  struct Footprint {
    int i0, i1, k0, k1;
  };
  std::vector<Footprint> foot_;
  std::vector<uint32_t> start_;
  std::vector<uint32_t> member_;
};

}  // namespace scour
