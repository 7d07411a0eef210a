#pragma once
// Scenes as data. A SceneSpec describes a scene in the units a person thinks in (metres, m³/s,
// parameters by name): the terrain as a generator with its settings, blocks of water, sources,
// sinks, effects. buildScene turns it into the engine's WorldDesc (particles on a lattice of the
// spec's Δs, the heightfield). Because overrides (`--set`) edit the spec before it is built, a
// new Δs refills the water at that spacing.
//
// Each preset is a scene file of assets/scenes/, built into the binary (builtin_scenes.h) and
// shared by the window, `scour run`, `scour bench` and the tests.

#include <stdexcept>
#include <string>
#include <vector>

#include "engine/world.h"

namespace scour {

/// Fractal (fBm) value noise added to a terrain: `octaves` layers, each of half the amplitude and
/// half the feature size of the one before, from a seeded lattice (same seed, same terrain).
struct NoiseSpec {
  double amplitude = 0.0;  ///< peak height of the first octave [m]; 0 = no noise
  double feature = 1.0;    ///< feature size (lattice spacing) of the first octave [m]
  int octaves = 4;
  int seed = 1;
};

/// A terrain over [0, length_x] × [0, length_z]: procedural, or a heightmap image. Every kind
/// adds `base`, the tilt `slope` · (length_x − x) (falling along +x) and the noise.
///   flat       nothing more
///   slope      the tilt alone
///   valley     plus a parabolic cross-section: side_rise · (2 (z − length_z/2) / length_z)²
///   bowl       a crater: a paraboloid rising to side_rise at the rim (radius `rim` × half the
///              shorter side, centred), falling linearly outside it to 0 at the edges
///   terraces   the tilt cut into `levels` flat steps with risers over a fraction `riser` of each
///              step, plus the valley cross-section
///   rolling    bumps of height `amplitude`: amplitude · sin(6πx / length_x) · cos(4πz / length_z)
///   fbm        the noise alone (with `slope`/`base`)
///   heightmap  an image (below), resampled and scaled to [height_min, height_max]
struct TerrainSpec {
  std::string kind = "flat";
  double length_x = 1.0, length_z = 1.0;  ///< extent [m]
  double cell = 0.05;                    ///< grid spacing (rounded to fit the extent) [m]
  double slope = 0.0;      ///< drop per metre along +x [-]
  double side_rise = 0.0;  ///< valley/terraces: sides above the axis; bowl: rim height [m]
  double amplitude = 0.0;  ///< rolling: height of the bumps [m]
  double base = 0.0;       ///< height added everywhere [m]
  int levels = 3;          ///< terraces: number of steps
  double riser = 0.15;     ///< terraces: fraction of a step taken by its riser
  double rim = 0.8;        ///< bowl: rim radius over half the shorter side
  NoiseSpec noise;
  // heightmap: a greyscale PNG (8 or 16 bit), raw float32 (.r32, needs raw_width/raw_height),
  // a float OpenEXR image (.exr, one channel) or a built-in image ("builtin:srtm-grand-canyon"),
  // cropped to [crop_x, crop_x + crop_w) × [crop_z, crop_z + crop_h) pixels (0 = whole image),
  // resampled bilinearly to the grid, and scaled so its lowest point is height_min and its
  // highest height_max (heights "scaled"), or its values kept as metres (heights "metres": float
  // files only). Image rows run along +z, columns along +x.
  std::string file;          ///< resolved path (relative paths are taken from the scene file)
  double height_min = 0.0, height_max = 1.0;  ///< [m]
  std::string heights = "scaled";  ///< "scaled" to [height_min, height_max], or "metres" as they are
  int crop_x = 0, crop_z = 0, crop_w = 0, crop_h = 0;  ///< [pixels]
  int raw_width = 0, raw_height = 0;  ///< .r32 only [pixels]
};

/// A flat terrain of the given extent and grid spacing [m].
inline TerrainSpec flatTerrain(double length_x, double length_z, double cell) {
  TerrainSpec t;
  t.length_x = length_x;
  t.length_z = length_z;
  t.cell = cell;
  return t;
}

/// An input error in a scene, with the JSON path of the field in its message (and the file,
/// where the scene came from one).
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Thrown for a heightmap that cannot be used (missing, not greyscale, too large, …).
struct TerrainError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A box of water on a lattice of spacing Δs. With `above_terrain`, only the lattice points at
/// least Δs/2 above the terrain are filled: a lake or river up to the box's top. With `flood`,
/// only the terrain below the box's top that is connected to the point `flood_from` (x, z) is
/// filled, as water poured there would: a lake stays inside its rim.
struct WaterBlock {
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();  ///< [m]
  bool above_terrain = false;
  bool flood = false;
  Eigen::Vector2d flood_from = Eigen::Vector2d::Zero();  ///< (x, z) [m]
};

/// Initial sediment: the particle nearest `position` starts at concentration c.
struct SedimentMark {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double c = 0.0;
};

/// How `--scale` resizes a scene (a scene file's "scaling"; docs/scene-format.md). The scale
/// multiplies the particle count, roughly:
///   spacing  Δs / ∛scale, everything else as it is (the default)
///   fixed    nothing changes (a lattice whose size is the experiment)
///   column   a dam break: Δs = width / max(4, round(cells ∛scale)), a whole number of cells
///            across the column, and the slab (terrain and water along z) slab_cells Δs deep
///   pool     Δs as it is; the pool's (x, z) side, its terrain's too, holds `particles` × scale
///            particles in `layers` layers (or the count `scour bench --particles` asks for)
struct Scaling {
  enum class Rule { kSpacing, kFixed, kColumn, kPool } rule = Rule::kSpacing;
  double width = 0.1;        ///< column: the column's width [m]
  int cells = 16;            ///< column: cells across it at scale 1
  int slab_cells = 6;        ///< column: the slab's depth [Δs]
  double particles = 1e5;    ///< pool: the count at scale 1
  int layers = 16;           ///< pool: its depth [Δs]
};

/// A parameter multiplied by `factor` once the simulated time reaches `time`.
struct ParamJump {
  double time;
  std::string key;
  double factor;
};

/// How `scour stress` runs a scene (a scene file's "stress"): for how long, and the parameter
/// jumps on the way. A duration of 0: the scene names none.
struct StressPlan {
  double duration = 0;  ///< simulated seconds
  std::vector<ParamJump> jumps;
};

struct SceneSpec {
  std::string name, description;
  SimParams params;
  TerrainSpec terrain;
  Domain domain;
  Effects effects;
  std::vector<WaterBlock> blocks;
  std::vector<Source> sources;
  std::vector<Sink> sinks;
  std::vector<Rain> rain;
  std::vector<SedimentMark> sediment;
  /// The view pictures are taken from (`scour run --frames`, `scour render`); none: an overview.
  bool has_camera = false;
  Eigen::Vector3d camera_eye = Eigen::Vector3d::Zero(), camera_target = Eigen::Vector3d::Zero();
  Scaling scaling;
  StressPlan stress;
};

/// A built scene: its spec and the engine's description made from it.
struct Scene {
  SceneSpec spec;
  WorldDesc desc;
};

struct PresetInfo {
  const char* name;
  const char* description;
};
/// The presets (the built-in scenes but the stress ones), in file-name order.
const std::vector<PresetInfo>& presetList();

/// The spec of a built-in scene (a preset or a stress scene), scaled by its rule (applyScaling).
/// Throws std::invalid_argument for an unknown name, naming the valid ones.
SceneSpec presetSpec(const std::string& name, double scale = 1.0, long particles = 0);
/// Resizes a scene by its scaling rule (Scaling): `scale` multiplies the particle count, roughly;
/// `particles` > 0 asks for about that many where the rule can (pool). Throws
/// std::invalid_argument for a scale that is not a positive number.
void applyScaling(SceneSpec& s, double scale, long particles = 0);

/// The terrain kinds, for messages and the GUI.
const std::vector<std::string>& terrainKinds();
/// Builds the heightfield of a terrain spec. Throws TerrainError for a bad heightmap.
Heightfield buildTerrain(const TerrainSpec& t);
/// Builds the engine's description: water blocks filled on a cubic lattice of spacing Δs (the
/// whole cells that fit, centred in the block, at hydrostatic pressure below their top), sediment
/// marks on the nearest particle. First checks the spec against the limits (checkFootprint),
/// then, on the built terrain, that its geometry makes sense (checkGeometry); throws SceneError
/// (or TerrainError for a heightmap) before the water is made.
Scene buildScene(const SceneSpec& spec);

/// The whole lattice cells of spacing Δs that fit a block, per axis: what buildScene fills and
/// estimateFootprint counts (doubles: an absurd block's count must not overflow before the
/// footprint refuses it).
Eigen::Vector3d blockLattice(const WaterBlock& b, double spacing);

/// What a scene asks of the machine, estimated before the water is made. Without the terrain,
/// water filled above it (above_terrain, flood_from) is not counted and `unknown` says so; with
/// it, such a block counts the columns between the terrain and its top.
struct Footprint {
  double vertices = 0;   ///< terrain grid vertices
  double particles = 0;  ///< water-block particles at Δs
  double bytes = 0;      ///< the memory estimate of engine/limits.h for both
  bool unknown = false;  ///< some water could not be counted without the terrain
};
Footprint estimateFootprint(const SceneSpec& spec, const Heightfield* terrain = nullptr);
/// Refuses a spec whose terrain, water, memory or per-step emission exceed engine/limits.h,
/// with the numbers and the field. Throws SceneError. buildScene calls it before building the
/// terrain (bounded by the vertex limit) and again with it.
void checkFootprint(const SceneSpec& spec, const Heightfield* terrain = nullptr);
/// Refuses geometry that would not run as written, naming the field: a source or flood point
/// off the terrain, a source below it, a rain rectangle that misses the terrain, a water block
/// beyond the domain or (without above_terrain) inside the terrain, or filling nothing, and
/// coordinates so far from the origin that float positions could not tell Δs/100 apart.
/// Throws SceneError.
void checkGeometry(const SceneSpec& spec, const Heightfield& terrain);

/// presetSpec + buildScene.
inline Scene makePreset(const std::string& name, double scale = 1.0, long particles = 0) {
  return buildScene(presetSpec(name, scale, particles));
}

}  // namespace scour
