#pragma once
// Data built into the binary: a heightmap named "builtin:…" in a scene is read from here.

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

}  // namespace scour
