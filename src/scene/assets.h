#pragma once
// Data built into the binary: a heightmap named "builtin:…" in a scene is read from here, and
// the built-in scenes (builtin_scenes.h) are these files.

#include <cstddef>
#include <string>
#include <vector>

namespace scour {

struct Asset {
  const char* name;  ///< "builtin:…"
  const unsigned char* data;
  size_t size;
};

const std::vector<Asset>& builtinAssets();
/// The asset of that name, or nullptr.
const Asset* findAsset(const std::string& name);
/// The scene files of assets/scenes/, named by their path there ("canyon.json",
/// "stress/cliffs.json"): the presets, then the stress scenes, each in file-name order.
const std::vector<Asset>& builtinSceneFiles();

}  // namespace scour
