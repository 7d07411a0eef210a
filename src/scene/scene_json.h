#pragma once
// Scene files (JSON, "version": 1; docs/scene-format.md) and the resolved scene written into
// summary.json. One format both ways: sceneToJson writes what specFromJson reads, so every preset
// round-trips. The reader is strict: every key must be known (an unknown one is refused with the
// nearest valid key), every value of the right type, finite and in range; a message names the
// file and the JSON path of the field (`sources[2].rate`), what was expected and what was found.

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "scene/presets.h"

namespace scour {

/// An input error in a scene file, with the file and JSON path in its message.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

nlohmann::json paramsToJson(const SimParams& p);
/// The spec of a scene: what specFromJson reads back.
nlohmann::json specToJson(const SceneSpec& s);
/// specToJson plus, under "built", what the spec built to (for people; not read back).
nlohmann::json sceneToJson(const Scene& s);
/// Reads a scene; `file` is used in messages. Throws SceneError.
SceneSpec specFromJson(const nlohmann::json& j, const std::string& file);
/// Parses a scene file. Throws SceneError (unreadable file, bad JSON, bad field).
SceneSpec loadSceneFile(const std::string& path);

}  // namespace scour
