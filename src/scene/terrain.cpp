// Terrains: the procedural generators and heightmap images (files or built into the binary).
#include <ImfChannelList.h>
#include <ImfCheckFile.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfStdIO.h>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>

#include "scene/assets.h"
#include "scene/geodata.h"
#include "scene/heightmap_size.h"
#include "scene/input_file.h"
#include "scene/presets.h"

namespace scour {

namespace {

// A greyscale image as doubles, row-major (rows along +z).
struct Gray {
  int w = 0, h = 0;
  std::vector<double> v;
};


Gray readRaw(const TerrainSpec& t) {
  const std::string& f = t.file;
  if (t.raw_width < 2 || t.raw_height < 2)
    throw TerrainError(f + ": a .r32 heightmap needs terrain.raw_size [width, height], each ≥ 2");
  if (1LL * t.raw_width * t.raw_height > kMaxHeightmapPixels)
    throw TerrainError(f + ": " + std::to_string(t.raw_width) + " × " +
                       std::to_string(t.raw_height) + " pixels is more than this build reads");
  // The file is exactly the grid: a longer one is another size (or another file), not a crop.
  const size_t want = size_t(t.raw_width) * t.raw_height * sizeof(float);
  size_t have = 0;
  try {
    have = checkInputFile(f, "heightmap", size_t(kMaxHeightmapPixels) * sizeof(float));
  } catch (const InputFileError& e) {
    throw TerrainError(e.what());
  }
  if (have != want)
    throw TerrainError(f + ": holds " + std::to_string(have) + " bytes, but terrain.raw_size [" +
                       std::to_string(t.raw_width) + ", " + std::to_string(t.raw_height) +
                       "] of float32 values is " + std::to_string(want) + " bytes");
  std::ifstream in(f, std::ios::binary);
  if (!in) throw TerrainError(f + ": cannot open the heightmap");
  std::vector<float> px(size_t(t.raw_width) * t.raw_height);
  in.read(reinterpret_cast<char*>(px.data()), std::streamsize(px.size() * sizeof(float)));
  if (in.gcount() != std::streamsize(px.size() * sizeof(float)))
    throw TerrainError(f + ": cannot read its " + std::to_string(want) + " bytes");
  Gray g;
  g.w = t.raw_width, g.h = t.raw_height;
  g.v.assign(px.begin(), px.end());
  return g;
}

// A PNG (or any image stb reads) from memory: it must be one channel, 8 or 16 bit.
Gray decodeImage(const std::string& f, const std::vector<unsigned char>& bytes) {
  const auto* data = bytes.data();
  const int size = int(bytes.size());
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(data, size, &w, &h, &comp))
    throw TerrainError(f + ": not a readable image (" + std::string(stbi_failure_reason()) + ")");
  if (comp != 1)
    throw TerrainError(f + ": expected a greyscale image, found " + std::to_string(comp) + " channels");
  // The run-length formats stb also reads pack far fewer pixels a byte than deflate (a 69-byte
  // file asking for 10⁸ pixels, 1 GB; a 49 kB one for 10⁸, found by the fuzzer).
  checkHeightmapSize(f, w, h, double(size), "image", "a PNG");
  Gray g;
  g.w = w, g.h = h;
  g.v.resize(size_t(w) * h);
  if (stbi_is_16_bit_from_memory(data, size)) {
    stbi_us* px = stbi_load_16_from_memory(data, size, &w, &h, &comp, 1);
    if (!px) throw TerrainError(f + ": cannot decode: " + stbi_failure_reason());
    for (size_t i = 0; i < g.v.size(); ++i) g.v[i] = px[i];
    stbi_image_free(px);
  } else {
    stbi_uc* px = stbi_load_from_memory(data, size, &w, &h, &comp, 1);
    if (!px) throw TerrainError(f + ": cannot decode: " + stbi_failure_reason());
    for (size_t i = 0; i < g.v.size(); ++i) g.v[i] = px[i];
    stbi_image_free(px);
  }
  return g;
}

bool endsWith(const std::string& s, const char* tail) {
  const std::string t(tail);
  return s.size() >= t.size() && s.compare(s.size() - t.size(), t.size(), t) == 0;
}

// A float OpenEXR image: its one channel (Y, or the first of R, G, B when it has those), any
// pixel type, read as float. OpenEXR's own message for a file it cannot read.
Gray readExr(const std::string& f) {
  std::string bytes;
  try {
    bytes = readInputFile(f, "heightmap", size_t(1) << 30);
  } catch (const InputFileError& e) {
    throw TerrainError(e.what());
  }
  // OpenEXR's own check for untrusted files first (bounded memory and time; what oss-fuzz runs):
  // a header may claim a size whose tables alone would not fit in memory.
  if (Imf::checkOpenEXRFile(bytes.data(), bytes.size(), true, true, true))
    throw TerrainError(f + ": not a readable OpenEXR image (OpenEXR's check of the file failed: damaged, "
                       "truncated or too large)");
  try {
    Imf::StdISStream stream;
    stream.str(bytes);
    Imf::InputFile file(stream);
    const Imath::Box2i win = file.header().dataWindow();
    const long long w = 1LL * win.max.x - win.min.x + 1, h = 1LL * win.max.y - win.min.y + 1;
    checkHeightmapSize(f, w, h, double(bytes.size()), "image", "an EXR");
    const Imf::ChannelList& channels = file.header().channels();
    std::string channel, names;
    for (auto c = channels.begin(); c != channels.end(); ++c) names += (names.empty() ? "" : ", ") + std::string(c.name());
    for (const char* want : {"Y", "R", "G", "B"})
      if (channel.empty() && channels.findChannel(want)) channel = want;
    if (channel.empty() && channels.begin() != channels.end() && ++channels.begin() == channels.end())
      channel = channels.begin().name();
    if (channel.empty())
      throw TerrainError(f + ": expected one channel (Y) or R, G, B; found " + (names.empty() ? "none" : names));
    Gray g;
    g.w = int(w), g.h = int(h);
    std::vector<float> px(size_t(w) * size_t(h));
    Imf::FrameBuffer fb;
    char* origin = reinterpret_cast<char*>(px.data() - (long long)win.min.x - (long long)win.min.y * w);
    fb.insert(channel, Imf::Slice(Imf::FLOAT, origin, sizeof(float), size_t(w) * sizeof(float)));
    file.setFrameBuffer(fb);
    file.readPixels(win.min.y, win.max.y);
    g.v.assign(px.begin(), px.end());
    return g;
  } catch (const TerrainError&) {
    throw;
  } catch (const std::exception& e) {
    throw TerrainError(f + ": not a readable OpenEXR image (" + e.what() + ")");
  }
}

Gray readHeightmap(const TerrainSpec& t) {
  const std::string& f = t.file;
  Gray g;
  if (endsWith(f, ".r32")) {
    g = readRaw(t);
  } else if (endsWith(f, ".exr")) {
    g = readExr(f);
  } else if (isGdalRaster(f)) {
    GeoRaster r = readGeoRaster(f);
    g.w = r.width, g.h = r.height, g.v = std::move(r.values);
  } else if (f.rfind("builtin:", 0) == 0) {
    const Asset* a = findAsset(f);
    if (!a) {
      std::string names;
      for (const Asset& x : builtinAssets()) names += std::string(names.empty() ? "" : ", ") + x.name;
      throw TerrainError(f + ": no such built-in heightmap (there is " + names + ")");
    }
    g = decodeImage(f, std::vector<unsigned char>(a->data, a->data + a->size));
  } else {
    std::string file;
    try {
      file = readInputFile(f, "heightmap", size_t(1) << 30);
    } catch (const InputFileError& e) {
      throw TerrainError(e.what());
    }
    g = decodeImage(f, std::vector<unsigned char>(file.begin(), file.end()));
  }
  for (double x : g.v)
    if (!std::isfinite(x)) throw TerrainError(f + ": holds a non-finite height");
  return g;
}

void fillFromHeightmap(const TerrainSpec& t, Heightfield& hf) {
  const Gray g = readHeightmap(t);
  const int cw = t.crop_w > 0 ? t.crop_w : g.w - t.crop_x, ch = t.crop_h > 0 ? t.crop_h : g.h - t.crop_z;
  if (t.crop_x < 0 || t.crop_z < 0 || cw < 2 || ch < 2 || t.crop_x + cw > g.w || t.crop_z + ch > g.h)
    throw TerrainError(t.file + ": the crop [" + std::to_string(t.crop_x) + ", " +
                       std::to_string(t.crop_z) + ", " + std::to_string(cw) + ", " +
                       std::to_string(ch) + "] does not fit the " + std::to_string(g.w) + " × " +
                       std::to_string(g.h) + " image");
  // Bilinear resampling of the crop onto the grid.
  for (int k = 0; k < hf.nz(); ++k)
    for (int i = 0; i < hf.nx(); ++i) {
      const double u = double(i) / (hf.nx() - 1) * (cw - 1), w = double(k) / (hf.nz() - 1) * (ch - 1);
      const int i0 = std::min(int(u), cw - 2), k0 = std::min(int(w), ch - 2);
      const double fu = u - i0, fw = w - k0;
      auto at = [&](int a, int b) { return g.v[size_t(t.crop_z + k0 + b) * g.w + t.crop_x + i0 + a]; };
      hf.at(i, k) = (1 - fw) * ((1 - fu) * at(0, 0) + fu * at(1, 0)) + fw * ((1 - fu) * at(0, 1) + fu * at(1, 1));
    }
  if (t.heights == "metres") {
    if (!endsWith(t.file, ".r32") && !endsWith(t.file, ".exr") && !isGdalRaster(t.file))
      throw TerrainError(t.file + ": terrain.heights \"metres\" needs elevation data or a float heightmap "
                         "(.tif, .hgt, .asc, … or .r32, .exr); an image's levels are not metres (use height_min and height_max)");
    return;  // the file's values, as they are
  }
  // Scale to the range the scene asks for.
  const double lo = hf.minHeight(), hi = hf.maxHeight(), span = hi > lo ? hi - lo : 1.0;
  for (double& h : hf.heights()) h = t.height_min + (h - lo) / span * (t.height_max - t.height_min);
}

// Value noise on an integer lattice: a hashed value in [−1, 1] at each lattice point, blended
// with a smoothstep.
double latticeValue(int64_t i, int64_t k, uint64_t seed) {
  uint64_t x = uint64_t(i) * 0x9E3779B97F4A7C15ULL ^ uint64_t(k) * 0xC2B2AE3D27D4EB4FULL ^
               seed * 0x165667B19E3779F9ULL;
  x ^= x >> 31, x *= 0xBF58476D1CE4E5B9ULL, x ^= x >> 29, x *= 0x94D049BB133111EBULL, x ^= x >> 32;
  return double(x >> 11) * 0x1.0p-52 - 1.0;
}

double valueNoise(double x, double z, uint64_t seed) {
  const double fx = std::floor(x), fz = std::floor(z);
  const int64_t i = int64_t(fx), k = int64_t(fz);
  auto smooth = [](double t) { return t * t * (3 - 2 * t); };
  const double u = smooth(x - fx), w = smooth(z - fz);
  const double a = latticeValue(i, k, seed), b = latticeValue(i + 1, k, seed);
  const double c = latticeValue(i, k + 1, seed), d = latticeValue(i + 1, k + 1, seed);
  return (1 - w) * ((1 - u) * a + u * b) + w * ((1 - u) * c + u * d);
}

double fbm(const NoiseSpec& n, double x, double z) {
  double sum = 0, amp = n.amplitude, size = n.feature;
  for (int o = 0; o < n.octaves; ++o, amp *= 0.5, size *= 0.5)
    sum += amp * valueNoise(x / size, z / size, uint64_t(n.seed) * 131 + uint64_t(o));
  return sum;
}

double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// The procedural height at (x, z).
double generated(const TerrainSpec& t, double x, double z) {
  const double across = 2.0 * (z - 0.5 * t.length_z) / t.length_z;
  const double tilt = t.slope * (t.length_x - x);
  double h = 0;
  if (t.kind == "slope") {
    h = tilt;
  } else if (t.kind == "valley") {
    h = tilt + t.side_rise * across * across;
  } else if (t.kind == "terraces") {
    // The tilt's total drop in `levels` equal steps: flat treads, smooth risers.
    const double u = (t.length_x - x) / t.length_x * t.levels;
    const double k = std::min(std::floor(u), double(t.levels - 1));
    const double step = t.slope * t.length_x / t.levels;
    h = step * (k + smoothstep((u - k - (1 - t.riser)) / t.riser)) + t.side_rise * across * across;
  } else if (t.kind == "bowl") {
    const double cx = 0.5 * t.length_x, cz = 0.5 * t.length_z;
    const double half = 0.5 * std::min(t.length_x, t.length_z), rim = t.rim * half;
    const double r = std::hypot(x - cx, z - cz);
    const double edge = std::hypot(std::max(cx, 0.0), std::max(cz, 0.0));  // farthest corner
    if (r <= rim)
      h = t.side_rise * (r / rim) * (r / rim);
    else
      h = t.side_rise * std::max(0.0, 1.0 - (r - rim) / (edge - rim));
    h += tilt;
  } else if (t.kind == "rolling") {
    h = t.amplitude * std::sin(2 * M_PI * 3 * x / t.length_x) * std::cos(2 * M_PI * 2 * z / t.length_z);
  } else if (t.kind == "fbm") {
    h = tilt;
  }
  return h;
}

}  // namespace

const std::vector<std::string>& terrainKinds() {
  static const std::vector<std::string> k = {"flat", "slope", "valley", "bowl", "terraces",
                                             "rolling", "fbm", "heightmap"};
  return k;
}

Heightfield buildTerrain(const TerrainSpec& t) {
  const int nx = std::max(2, int(std::round(t.length_x / t.cell)) + 1);
  const int nz = std::max(2, int(std::round(t.length_z / t.cell)) + 1);
  Heightfield hf(nx, nz, t.length_x / (nx - 1), t.length_z / (nz - 1));
  if (t.kind == "heightmap") fillFromHeightmap(t, hf);
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const double x = i * hf.dx(), z = k * hf.dz();
      double h = t.base;
      if (t.kind == "heightmap")
        h += hf.at(i, k) + t.slope * (t.length_x - x);
      else
        h += generated(t, x, z);
      if (t.noise.amplitude != 0) h += fbm(t.noise, x, z);
      hf.at(i, k) = h;
    }
  return hf;
}

}  // namespace scour
