#pragma once
// The built-in scenes: the scene files of assets/scenes/ (the presets: the paper's scenes, the
// tests' and the benchmark's) and assets/scenes/stress/ (`scour stress`), built into the binary
// and read by the one scene reader. A file's "name" is its file name's stem (a stress scene's
// with "stress-" before it), so `scour canyon`, `scour run canyon` and
// `scour run assets/scenes/canyon.json` run the same scene.

#include <string>
#include <vector>

#include "scene/presets.h"

namespace scour {

/// A built-in scene; its name and description are its spec's (the file's own).
struct BuiltinScene {
  std::string file;     ///< how messages name it: "builtin:scenes/canyon.json"
  bool stress = false;  ///< one of assets/scenes/stress/
  SceneSpec spec;       ///< as read, before any --scale
};

/// Every built-in scene, the presets first, each group in file-name order; read once.
const std::vector<BuiltinScene>& builtinScenes();
/// The scene of that name, or nullptr.
const BuiltinScene* findBuiltinScene(const std::string& name);
/// The names, for messages: "block, canyon, …".
std::string builtinSceneNames();

}  // namespace scour
