#pragma once
// Checkpoints: a run's scene and its world state in one file, so `scour run --resume FILE` needs
// nothing else and continues bit for bit.
//
// Layout (little-endian):
//   "SCOURCKP"  8 bytes magic
//   u32         format version (kCheckpointVersion)
//   u64         payload length in bytes
//   payload     u64 length + scene JSON text, then World::saveState
//   u64         FNV-1a 64 of the payload
// Written to a temporary file and renamed; a truncated, corrupted or other-version file is refused
// with a CheckpointError naming the file and what is wrong.

#include <stdexcept>
#include <string>

#include "engine/world.h"
#include "scene/presets.h"

namespace scour {

constexpr uint32_t kCheckpointVersion = 1;
/// Largest checkpoint read [bytes] (a run at the particle limit writes less).
constexpr size_t kMaxCheckpointBytes = size_t(8) << 30;

struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Writes the scene (as its spec: a checkpoint need not build it) and the world's state to `path`
/// (atomically).
void writeCheckpoint(const std::string& path, const SceneSpec& spec, const World& world);

/// A checkpoint read back: the scene (rebuilt from its JSON) and the world state to load.
struct Checkpoint {
  SceneSpec spec;
  std::string state;  ///< World::saveState bytes
};
Checkpoint readCheckpoint(const std::string& path);

/// Builds the World of a checkpoint and loads its state.
World resumeWorld(const Checkpoint& c, Scene& scene);

}  // namespace scour
