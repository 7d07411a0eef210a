// scour export: the heights and the erosion maps of a checkpoint, in the formats an engine takes
// (docs/exports.md), so a long run is exported once it is done, and again in another format later.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "engine/maps.h"
#include "scene/checkpoint.h"
#include "scene/gltf.h"
#include "scene/output.h"
#include "scene/run_outputs.h"

namespace scour {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct ExportOptions {
  std::string checkpoint, out, maps = "all", format = "png16", resample, mesh = "none";
};

// "WxH" vertices, each side 2 to 16,385; InputError naming --resample otherwise.
std::pair<int, int> parseGridSize(const std::string& text) {
  const size_t x = text.find('x');
  auto side = [&](const std::string& part) {
    char* end = nullptr;
    const long v = std::strtol(part.c_str(), &end, 10);
    if (part.empty() || end != part.c_str() + part.size() || v < 2 || v > 16385)
      throw InputError("--resample: expected WxH vertices, each 2 to 16385 (Unreal: 1009x1009, "
                       "2017x2017; Unity: 1025x1025), found '" + text + "'");
    return int(v);
  };
  if (x == std::string::npos) side("");
  const int w = side(text.substr(0, x)), h = side(text.substr(x + 1));
  // Heights, their copy and the maps as doubles: 2²⁷ vertices is about 5 GB already.
  if (1LL * w * h > (1LL << 27))
    throw InputError("--resample: " + text + " is " + std::to_string(1LL * w * h) +
                     " vertices, more than this build writes (134,217,728)");
  return {w, h};
}

int exportCheckpoint(const ExportOptions& o) {
  if (o.format != "png16" && o.format != "r16" && o.format != "exr" && o.format != "geotiff")
    throw InputError("--format: expected png16, r16, exr or geotiff, found '" + o.format + "'");
  if (o.mesh != "none" && o.mesh != "gltf" && o.mesh != "obj")
    throw InputError("--mesh: expected none, gltf or obj, found '" + o.mesh + "'");
  const std::pair<int, int> size = o.resample.empty() ? std::pair<int, int>{0, 0} : parseGridSize(o.resample);
  std::vector<std::string> maps;
  try {
    maps = parseMapNames("--maps", o.maps);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  Scene scene;
  const std::unique_ptr<World> world = resumeFromCheckpoint(o.checkpoint, scene, "");
  // GeoTIFF: the input elevation data's georeference, read again from terrain.file (before
  // anything is written: a file that is gone or unreadable is refused).
  Georeference where;
  if (o.format == "geotiff") {
    try {
      where = gridGeoreference(scene.spec.terrain, world->terrain().nx(), world->terrain().nz());
    } catch (const TerrainError& e) {
      throw InputError(std::string("terrain.file of the checkpoint's scene: ") + e.what());
    }
  }
  std::error_code ec;
  // A run's own folder keeps its run's heights: an export goes elsewhere.
  if (fs::exists(fs::path(o.out) / "summary.json", ec))
    throw InputError("--out: '" + o.out + "' holds a run's outputs (summary.json); export into another folder");
  createOutputDirectory("--out", o.out);
  const fs::path dir(o.out);
  const Heightfield settled = world->settledTerrain();
  std::vector<TerrainMap> mapValues = erosionMaps(*world, maps);
  // --resample: the same rectangle on the engine's grid, heights and maps alike.
  Heightfield hf = settled;
  if (size.first > 0) {
    const int nx = settled.nx(), nz = settled.nz();
    hf = Heightfield(size.first, size.second, settled.dx() * (nx - 1) / (size.first - 1),
                     settled.dz() * (nz - 1) / (size.second - 1), settled.x0(), settled.z0());
    hf.heights() = resampleGrid(settled.heights(), nx, nz, size.first, size.second);
    for (TerrainMap& m : mapValues) {
      m.values = resampleGrid(m.values, nx, nz, size.first, size.second);
      if (!m.second.empty()) m.second = resampleGrid(m.second, nx, nz, size.first, size.second);
    }
    // The same rectangle: vertex (0, 0) stays where it was, the pixels shrink or grow.
    if (where.valid)
      where = resampledGeoreference(where, 0, 0, double(nx - 1) / (size.first - 1), double(nz - 1) / (size.second - 1));
  }
  const bool georeferenced = where.valid;
  if (o.format == "geotiff" && !where.valid) where = localGeoreference(hf.x0(), hf.z0(), hf.dx(), hf.dz());
  json heights = {{"nx", hf.nx()}, {"nz", hf.nz()}, {"dx_m", hf.dx()}, {"dz_m", hf.dz()},
                  {"x0_m", hf.x0()}, {"z0_m", hf.z0()}};
  if (o.format == "png16") {
    const auto [lo, hi] = writeHeightPng16(dir / "height.png", hf);
    heights["file"] = "height.png", heights["min_m"] = lo, heights["max_m"] = hi;
    heights["mapping"] = "h = min_m + v / 65535 * (max_m - min_m); row k is z = z0 + k dz, column i is x = x0 + i dx";
  } else if (o.format == "exr") {
    writeGridExr(dir / "height.exr", hf.nx(), hf.nz(), hf.heights());
    heights["file"] = "height.exr", heights["min_m"] = hf.minHeight(), heights["max_m"] = hf.maxHeight();
    heights["mapping"] = "float32 channel Y, the height in metres; row k is z = z0 + k dz, column i is x = x0 + i dx";
  } else if (o.format == "geotiff") {
    const TerrainSpec& t = scene.spec.terrain;
    std::map<std::string, std::string> meta = {
        {"SCOUR_CHECKPOINT", o.checkpoint},
        {"SCOUR_STEP", std::to_string(world->steps())},
        {"SCOUR_HEIGHTS", "metres at the scene's scale" + std::string(t.kind == "heightmap" && t.heights == "scaled" ? " (the input scaled to terrain.height_min..height_max)" : "")}};
    writeGeoTiff(dir / "height.tif", hf.nx(), hf.nz(), {&hf.heights()}, where, "m", meta);
    heights["file"] = "height.tif", heights["min_m"] = hf.minHeight(), heights["max_m"] = hf.maxHeight();
    heights["mapping"] = "float32 band 1, the height in metres at the scene's scale; row k is z = z0 + k dz, column i is x = x0 + i dx";
    heights["georeference"] = georeferenced ? json{{"from", t.file}, {"geotransform", where.transform}, {"crs_wkt", where.crs}}
                                            : json{{"from", "none: local metres from the grid's origin"}, {"geotransform", where.transform}};
  } else {
    const auto [lo, hi] = writeHeightR16(dir / "height.r16", hf);
    heights["file"] = "height.r16", heights["min_m"] = lo, heights["max_m"] = hi;
    heights["mapping"] = "uint16 little-endian, nz rows of nx; h = min_m + v / 65535 * (max_m - min_m)";
    // Unreal's landscape spans 512 × Z scale cm over the 65,536 levels; X and Y scale are the
    // grid's spacing in cm.
    heights["unreal_scale_cm"] = {hf.dx() * 100, hf.dz() * 100, (hi - lo) * 100 / 512};
  }
  writeHeightRaw(dir / "height.r32", hf);
  json mesh = nullptr;
  if (o.mesh == "obj") {
    writeTerrainObj(dir / "terrain.obj", hf);
    mesh = {{"file", "terrain.obj"}};
  } else if (o.mesh == "gltf") {
    // The maps asked for, as per-vertex attributes.
    const std::vector<std::string> attributes = writeTerrainGltf(dir / "terrain.glb", hf, mapValues);
    mesh = {{"file", "terrain.glb"},
            {"attributes", attributes},
            {"mapping", "binary glTF 2.0, y up, metres; TEXCOORD_0 u = i / (nx - 1), v = k / (nz - 1) (the map images lie on it); each map a per-vertex float attribute in its unit"}};
  }
  if (size.first > 0) heights["resampled_from"] = {settled.nx(), settled.nz()};
  json summary = {{"checkpoint", o.checkpoint},
                  {"step", world->steps()},
                  {"hydraulic_s", world->time()},
                  {"morphological_s", world->morphologicalTime()},
                  {"heights", heights},
                  {"height_r32", "float32 little-endian, nz rows of nx heights [m]"},
                  {"mesh", mesh},
                  {"maps", maps.empty() ? json(nullptr) : writeErosionMaps(dir / "maps", mapValues, hf.nx(), hf.nz(), maps,
                                                                   o.format == "exr" ? MapFormat::kExr : o.format == "geotiff" ? MapFormat::kGeoTiff : MapFormat::kPng16,
                                                                   &where)}};
  writeAtomically(dir / "export.json", [&](std::ostream& out) { out << summary.dump(2) << "\n"; });
  std::cout << "exported step " << world->steps() << " of " << o.checkpoint << " (" << hf.nx() << " x "
            << hf.nz() << " heights, " << maps.size() << " maps) to " << dir.string() << "\n";
  return kExitOk;
}

}  // namespace

Command addExportCommand(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* c = app.add_subcommand("export", "Write a checkpoint's heights and erosion maps for an engine");
  c->add_option("checkpoint", o->checkpoint, "A checkpoint (.ckpt) of scour run")->required();
  c->add_option("--out", o->out, "Output directory")->required();
  c->add_option("--maps", o->maps, "Erosion maps: all (default), none, or a list of wear, deposition, sediment, flow, wetness, shear_peak, shear_mean, flow_direction");
  c->add_option("--mesh", o->mesh, "The terrain as a mesh too: none (default), gltf (terrain.glb, the maps as vertex attributes) or obj");
  c->add_option("--resample", o->resample,
                "Resample heights and maps to WxH vertices over the same rectangle (Unreal: 1009x1009, 2017x2017, 4033x4033; Unity: 513x513, 1025x1025, 2049x2049)");
  c->add_option("--format", o->format, "Heights (and maps) as png16 (16-bit PNG; default), r16 (Unreal's 16-bit raw heights, PNG maps), exr (float32 OpenEXR) or geotiff (float32 GeoTIFF with the input elevation data's georeference)");
  return [o] { return exportCheckpoint(*o); };
}

}  // namespace scour
