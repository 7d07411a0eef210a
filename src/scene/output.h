#pragma once
// Output files. Every writer goes through writeAtomically: the bytes go to a temporary file next
// to the target, which is renamed over it only when complete, so an interrupted run never leaves
// half a file.

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

#include "engine/fluid.h"

namespace scour {

/// Writes via `fill` into "<path>.tmp-<pid>" and renames it to `path`. Throws std::runtime_error
/// naming the file if anything fails (the temporary is removed).
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(std::ostream&)>& fill);

/// Binary little-endian PLY of the fluid particles: x y z vx vy vz (float), with the simulated
/// time in a `comment time_s` header line. y is up.
void writeParticlesPly(const std::filesystem::path& path, const Fluid& f, double time);

}  // namespace scour
