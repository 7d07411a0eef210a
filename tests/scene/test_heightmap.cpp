// Heightmap import: the real SRTM Grand Canyon tile (16-bit PNG) at the paper's 700 × 350 grid,
// 8-bit and raw float files, and the refusals (colour, missing, corrupt, wrong size).
#include <catch2/catch.hpp>
#include <stb_image_write.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "scene/presets.h"

using namespace scour;
namespace fs = std::filesystem;

namespace {
const std::string kTile = std::string(SCOUR_SOURCE_DIR) + "/assets/srtm-grand-canyon-N36W113-r2400-c2400.png";

fs::path tempDir() {
  fs::path d = fs::temp_directory_path() / ("scour_hm_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}
TerrainSpec heightmap(const std::string& file) {
  TerrainSpec t;
  t.kind = "heightmap";
  t.file = file;
  t.length_x = 699.0;
  t.length_z = 349.0;
  t.cell = 1.0;  // 700 × 350 vertices, the paper's canyon grid
  t.height_min = 660.0;
  t.height_max = 2804.0;
  return t;
}
}  // namespace

TEST_CASE("the SRTM tile imports at 700 × 350 with its height range and 16-bit precision",
          "[heightmap]") {
  TerrainSpec t = heightmap(kTile);
  t.crop_x = 0, t.crop_z = 300, t.crop_w = 1200, t.crop_h = 600;
  Heightfield hf = buildTerrain(t);
  CHECK(hf.nx() == 700);
  CHECK(hf.nz() == 350);
  CHECK(hf.minHeight() == Approx(660.0).epsilon(1e-12));
  CHECK(hf.maxHeight() == Approx(2804.0).epsilon(1e-12));
  std::set<double> distinct(hf.heights().begin(), hf.heights().end());
  INFO(distinct.size() << " distinct heights");
  CHECK(distinct.size() > 1000);  // no terracing: 8 bits would give at most 256
  // The river: the lowest 1 % of the grid lies far below the rim.
  std::vector<double> h = hf.heights();
  std::nth_element(h.begin(), h.begin() + h.size() / 100, h.end());
  CHECK(h[h.size() / 100] < 1200.0);
}

TEST_CASE("8-bit PNG and raw float heightmaps import; bad ones are refused", "[heightmap]") {
  fs::path d = tempDir();
  // A 4 × 3 ramp as 8-bit grey, as RGB, and as raw float.
  unsigned char grey[12], rgb[36];
  std::vector<float> raw(12);
  for (int i = 0; i < 12; ++i) {
    grey[i] = static_cast<unsigned char>(20 * i);
    rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = grey[i];
    raw[size_t(i)] = float(i);
  }
  REQUIRE(stbi_write_png((d / "g.png").c_str(), 4, 3, 1, grey, 4));
  REQUIRE(stbi_write_png((d / "c.png").c_str(), 4, 3, 3, rgb, 12));
  std::ofstream((d / "r.r32"), std::ios::binary)
      .write(reinterpret_cast<const char*>(raw.data()), std::streamsize(raw.size() * 4));
  {
    std::ifstream in(d / "g.png", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(d / "truncated.png", std::ios::binary) << bytes.substr(0, 30);
    std::ofstream(d / "empty.png", std::ios::binary);
  }
  TerrainSpec t = heightmap((d / "g.png").string());
  t.length_x = 3, t.length_z = 2, t.height_min = 0, t.height_max = 220;
  Heightfield g = buildTerrain(t);
  REQUIRE(g.nx() == 4);
  CHECK(g.at(3, 2) == Approx(220.0));
  CHECK(g.at(1, 0) == Approx(20.0));
  t.file = (d / "r.r32").string();
  t.raw_width = 4, t.raw_height = 3;
  Heightfield r = buildTerrain(t);
  CHECK(r.at(2, 1) == Approx(6.0 * 20.0));
  auto refusal = [&](const std::string& file, int rw = 0) {
    TerrainSpec b = t;
    b.file = file;
    b.raw_width = rw, b.raw_height = rw ? 3 : 0;
    try {
      buildTerrain(b);
    } catch (const TerrainError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  CHECK_THAT(refusal((d / "c.png").string()), Catch::Contains("expected a greyscale image, found 3 channels"));
  CHECK_THAT(refusal((d / "nope.png").string()), Catch::Contains("cannot open the heightmap"));
  CHECK_THAT(refusal((d / "truncated.png").string()), Catch::Contains("truncated.png: cannot decode") ||
                                                         Catch::Contains("not a readable image"));
  CHECK_THAT(refusal((d / "empty.png").string()), Catch::Contains("not a readable image"));
  CHECK_THAT(refusal((d / "r.r32").string(), 0), Catch::Contains("needs terrain.raw_size [width, height]"));
  CHECK_THAT(refusal((d / "r.r32").string(), 9),
             Catch::Contains("holds 48 bytes, but terrain.raw_size [9, 3] of float32 values is 108 bytes"));
  CHECK_THAT(refusal((d / "r.r32").string(), 2),  // a longer file is another size, not a crop
             Catch::Contains("holds 48 bytes, but terrain.raw_size [2, 3] of float32 values is 24 bytes"));
  CHECK_THAT(refusal(d.string()), Catch::Contains("is a directory, not a heightmap"));
  TerrainSpec crop = heightmap((d / "g.png").string());
  crop.crop_x = 3, crop.crop_w = 4;
  CHECK_THROWS_WITH(buildTerrain(crop), Catch::Contains("does not fit the 4 × 3 image"));
  fs::remove_all(d);
}
