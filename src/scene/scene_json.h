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

nlohmann::json paramsToJson(const SimParams& p);
/// The spec of a scene: what specFromJson reads back.
nlohmann::json specToJson(const SceneSpec& s);
/// specToJson plus, under "built", what the spec built to (for people; not read back).
nlohmann::json sceneToJson(const Scene& s);
/// Reads a scene; `file` is used in messages. Throws SceneError.
SceneSpec specFromJson(const nlohmann::json& j, const std::string& file);
/// Parses a scene file. Throws SceneError (unreadable file, bad JSON, bad field).
SceneSpec loadSceneFile(const std::string& path);

/// Deepest nesting of arrays and objects a scene file may have (the scene format needs 4).
constexpr int kMaxJsonDepth = 32;
/// Largest scene file read [bytes].
constexpr size_t kMaxSceneFileBytes = size_t(16) << 20;
/// Parses JSON text strictly: nesting deeper than kMaxJsonDepth, a key given twice in one object
/// and a number beyond double range are refused (naming the JSON path), as is invalid JSON.
/// Messages quote at most a short excerpt of the input. Throws SceneError prefixed with `file`.
nlohmann::json parseJsonText(const std::string& text, const std::string& file);
/// At most `limit` characters of `text`, with "..." when cut (for quoting input in messages).
std::string excerpt(const std::string& text, size_t limit = 60);

}  // namespace scour
