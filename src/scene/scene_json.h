#pragma once
// The resolved scene as JSON: every parameter (from the one parameter table), the terrain's
// geometry, the water blocks, sources and sinks. Written into summary.json so a run says exactly
// what it simulated.

#include <nlohmann/json.hpp>

#include "scene/presets.h"

namespace scour {

nlohmann::json paramsToJson(const SimParams& p);
nlohmann::json sceneToJson(const Scene& s);

}  // namespace scour
