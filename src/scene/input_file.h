#pragma once
// Reading a file the user named (a scene, a heightmap, a checkpoint, a replay script): it must be
// a regular file no larger than the reader's limit. Each reader turns the error into its own kind
// (SceneError, TerrainError, CheckpointError) so the message keeps naming the field or flag.

#include <cstddef>
#include <stdexcept>
#include <string>

namespace scour {

struct InputFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The whole file. `what` names it in messages ("scene file", "heightmap"): "PATH: cannot open
/// the WHAT", "PATH: is a directory, not a WHAT", "PATH: the WHAT is N bytes, more than the M
/// this build reads". Throws InputFileError.
std::string readInputFile(const std::string& path, const std::string& what, size_t maxBytes);

/// Checks the same without reading: an existing regular file of at most maxBytes. Throws
/// InputFileError. Returns its size.
size_t checkInputFile(const std::string& path, const std::string& what, size_t maxBytes);

}  // namespace scour
