#pragma once
// The terrain as a binary glTF 2.0 mesh (.glb, through tinygltf): one vertex per grid point with
// its normal and texture coordinates (u along x, v along z, so the map images of docs/exports.md
// lie on it as textures), two triangles per cell as in the engine, and the erosion maps as
// per-vertex attributes (_WEAR, _DEPOSITION, …, _FLOW_DIRECTION as a VEC2): glTF's
// application-specific attributes, which Blender imports as colour or generic attributes and
// Houdini as point attributes. y is up, in metres.

#include <filesystem>
#include <vector>

#include "engine/heightfield.h"
#include "engine/maps.h"

namespace scour {

/// Writes `hf` and the maps (each with hf's vertex count) to `path` (atomically). Returns the
/// attribute names written for the maps.
std::vector<std::string> writeTerrainGltf(const std::filesystem::path& path, const Heightfield& hf,
                                          const std::vector<TerrainMap>& maps);

}  // namespace scour
