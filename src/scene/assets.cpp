// Files the binary carries, so `scour` runs with no files at all. The bytes are included at
// assembly time (.incbin) straight from assets/, so nothing is generated and the repo holds the
// file once. SCOUR_ASSET_DIR is set by the build.
#include "scene/assets.h"

#define SCOUR_STR2(x) #x
#define SCOUR_STR(x) SCOUR_STR2(x)

asm(".section .rodata\n"
    ".balign 16\n"
    "scour_asset_srtm_begin:\n"
    ".incbin \"" SCOUR_STR(SCOUR_ASSET_DIR) "/srtm-grand-canyon-N36W113-r2400-c2400.png\"\n"
    "scour_asset_srtm_end:\n"
    ".previous\n");

extern "C" const unsigned char scour_asset_srtm_begin[];
extern "C" const unsigned char scour_asset_srtm_end[];

namespace scour {

const std::vector<Asset>& builtinAssets() {
  static const std::vector<Asset> list = {
      {"builtin:srtm-grand-canyon", scour_asset_srtm_begin,
       size_t(scour_asset_srtm_end - scour_asset_srtm_begin)},
  };
  return list;
}

const Asset* findAsset(const std::string& name) {
  for (const Asset& a : builtinAssets())
    if (name == a.name) return &a;
  return nullptr;
}

}  // namespace scour
