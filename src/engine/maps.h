#pragma once
// Erosion maps on the terrain's grid, for texturing an eroded terrain in an engine (issue 17,
// docs/exports.md): one value per vertex, row-major like the heights (row k is z = z0 + k·dz,
// column i is x = x0 + i·dx). Each is consistent with the soil ledger by construction: Σ map ×
// vertex area gives the eroded, deposited or suspended volume to rounding.

#include <string>
#include <vector>

namespace scour {

class World;

struct TerrainMap {
  std::string name;     ///< "wear", "deposition", "sediment"
  std::string unit;     ///< of each value
  std::string meaning;  ///< one line for a sidecar file or a panel
  std::vector<double> values;
  /// A second channel (flow_direction: values the x and this the z component), else empty.
  std::vector<double> second;
};

/// The maps' names, in the order erosionMaps returns them.
const std::vector<std::string>& erosionMapNames();

/// wear: the depth eroded at each vertex, max(0, −Δh) [m]; deposition: the depth deposited,
/// max(0, Δh) [m], both of the settled terrain against the start (World::heightChange), so Σ
/// wear·A_v is summary.json's eroded volume and Σ deposition·A_v its deposited volume;
/// sediment: the sediment suspended above each vertex now, as a depth of soil [m] (each
/// particle's sediment shared among the four corners of the grid cell under it by bilinear
/// weights, over the corner's area A_v; a particle beyond the terrain's edge counts at the
/// nearest point of it), so Σ sediment·A_v is the suspended volume. Then what the flow record
/// (flow_record.h) accumulated over the run: flow, the near-bed water that passed over each
/// vertex per unit width [m³/m]; wetness, its wet bed time over the recorded bed time [0, 1];
/// shear_peak and shear_mean, the largest τ and its mean over the wet time [Pa]; flow_direction,
/// the unit vector of the summed near-bed flow (x in values, z in second; 0 where none passed).
std::vector<TerrainMap> erosionMaps(const World& w, const std::vector<std::string>& names = erosionMapNames());
/// The one map called `name` (only its own work; std::invalid_argument for a name that is none).
TerrainMap erosionMap(const World& w, const std::string& name);
/// Whether `name` is one of erosionMapNames().
bool isErosionMap(const std::string& name);

/// Values on an nx × nz grid resampled bilinearly onto nx2 × nz2 points spanning the same
/// rectangle (the corners kept exactly): for an engine's preferred sizes (Unreal's 1009, 2017,
/// 4033 vertices, Unity's 513, 1025, 2049). Sums over the grid do not survive resampling: the
/// ledger's identities hold on the terrain's own grid.
std::vector<double> resampleGrid(const std::vector<double>& v, int nx, int nz, int nx2, int nz2);

}  // namespace scour
