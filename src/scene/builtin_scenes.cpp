#include "scene/builtin_scenes.h"

#include <stdexcept>
#include <string_view>

#include "scene/assets.h"
#include "scene/scene_json.h"

namespace scour {

namespace {

BuiltinScene readBuiltin(const Asset& a) {
  BuiltinScene b;
  const std::string path = a.name;  // "canyon.json", "stress/cliffs.json"
  b.file = "builtin:scenes/" + path;
  b.stress = path.rfind("stress/", 0) == 0;
  const std::string stem = path.substr(b.stress ? 7 : 0, path.size() - (b.stress ? 7 : 0) - 5);
  const std::string text(reinterpret_cast<const char*>(a.data), a.size);
  b.spec = specFromJson(parseJsonText(text, b.file), b.file);
  // The name opens the file: they must agree (a test reads every file).
  if (b.spec.name != (b.stress ? "stress-" : "") + stem)
    throw std::logic_error(b.file + ": name '" + b.spec.name + "' does not match the file's name");
  return b;
}

}  // namespace

const std::vector<BuiltinScene>& builtinScenes() {
  static const std::vector<BuiltinScene> scenes = [] {
    std::vector<BuiltinScene> out;
    for (const Asset& a : builtinSceneFiles()) out.push_back(readBuiltin(a));
    return out;
  }();
  return scenes;
}

const BuiltinScene* findBuiltinScene(const std::string& name) {
  for (const BuiltinScene& b : builtinScenes())
    if (b.spec.name == name) return &b;
  return nullptr;
}

std::string builtinSceneNames() {
  std::string names;
  for (const BuiltinScene& b : builtinScenes()) names += (names.empty() ? "" : ", ") + b.spec.name;
  return names;
}

}  // namespace scour
