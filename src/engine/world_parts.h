#pragma once
// What the World's files share inside the engine (world.cpp: construction and the step;
// world_supply.cpp: sources, sinks, rain, the brush and placement; world_ledger.cpp: the soil
// and energy ledgers and the invariants; world_state.cpp: the state hash, saving and loading).
// Not for use outside src/engine/.

#include <chrono>
#include <string>

#include "engine/world.h"

namespace scour::detail {

/// Throws std::invalid_argument(what) unless ok.
void require(bool ok, const std::string& what);
/// A source checked against the limits (engine/limits.h) before its slots are made; `at` names
/// it in messages ("sources[2]"). Throws std::invalid_argument.
Emitter makeEmitter(const Source& src, const SimParams& p, const std::string& at);
/// Throws std::invalid_argument unless the box has max > min on every axis.
void validateSink(const Sink& s, const std::string& at);
/// What the walls see of the terrain: its Δs/2 envelope (WallSurface).
inline WallSurface wallSurfaceFor(const Heightfield& terrain, const SimParams& p) {
  return WallSurface(terrain, 0.5 * p.spacing);
}

}  // namespace scour::detail

namespace scour {

/// Runs a pass and adds its time to its entry of passSeconds().
template <class F>
void World::timed(Pass pass, F&& f) {
  auto t0 = std::chrono::steady_clock::now();
  f();
  passSeconds_[size_t(pass)] +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++passCalls_[size_t(pass)];
}

}  // namespace scour
