// Heightmap files on any bytes: the first byte chooses a PNG (decoded from the header on), a raw
// float32 .r32 of a size from the next two bytes, a float OpenEXR image, or a GeoTIFF or an ASCII
// grid read through GDAL (GDAL itself is not instrumented: what is fuzzed is our side of it,
// the size checks and the NoData fill). Refused (TerrainError) or built, nothing else.
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "scene/presets.h"

using namespace scour;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 3) return 0;
  static const std::string dir = [] {
    char tmpl[] = "/tmp/scour_fuzz_hm_XXXXXX";
    return std::string(mkdtemp(tmpl));
  }();
  const int kind = data[0] % 5;  // 0 PNG, 1 raw, 2 EXR, 3 GeoTIFF, 4 ASCII grid
  const bool raw = kind == 1;
  static const char* const names[] = {"/h.png", "/h.r32", "/h.exr", "/h.tif", "/h.asc"};
  const std::string path = dir + names[kind];
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 3), std::streamsize(size - 3));
  }
  TerrainSpec t;
  t.kind = "heightmap";
  t.file = path;
  t.length_x = t.length_z = 1.0;
  t.cell = 0.1;
  if (kind >= 2 && (data[1] & 1)) t.heights = "metres";
  if (raw) t.raw_width = 1 + data[1] % 64, t.raw_height = 1 + data[2] % 64;
  try {
    buildTerrain(t);
  } catch (const TerrainError&) {
  }
  return 0;
}
