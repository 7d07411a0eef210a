// Terrain exports read back: the 16-bit PNG keeps 16-bit precision and the stated mapping, the
// raw float file is row-major little-endian, the erosion map colours erosion red and deposition
// blue; the particle PLY carries C.
#include <catch2/catch.hpp>
#include <stb_image.h>
#include <tiny_gltf.h>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <Eigen/Geometry>

#include "scene/gltf.h"
#include "scene/output.h"

using namespace scour;
namespace fs = std::filesystem;

namespace {
fs::path tempDir() {
  fs::path d = fs::temp_directory_path() / ("scour_exports_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST_CASE("16-bit height PNG and raw float heights read back", "[exports]") {
  Heightfield hf(37, 23, 1.0, 2.0);
  for (int k = 0; k < hf.nz(); ++k)
    for (int i = 0; i < hf.nx(); ++i) hf.at(i, k) = 100.0 + 0.37 * i * i + 3.1 * k;
  fs::path d = tempDir();
  auto [lo, hi] = writeHeightPng16(d / "h.png", hf);
  CHECK(lo == hf.minHeight());
  CHECK(hi == hf.maxHeight());
  int w = 0, h = 0, comp = 0;
  stbi_us* px = stbi_load_16((d / "h.png").c_str(), &w, &h, &comp, 0);
  REQUIRE(px);
  CHECK(w == 37);
  CHECK(h == 23);
  CHECK(comp == 1);
  double worst = 0;
  for (int k = 0; k < h; ++k)
    for (int i = 0; i < w; ++i) {
      double back = lo + px[k * w + i] / 65535.0 * (hi - lo);
      worst = std::max(worst, std::abs(back - hf.at(i, k)));
    }
  stbi_image_free(px);
  CHECK(worst <= 0.5 / 65535.0 * (hi - lo) * 1.0000001);  // half a 16-bit step

  writeHeightRaw(d / "h.r32", hf);
  REQUIRE(fs::file_size(d / "h.r32") == size_t(37 * 23 * 4));
  std::ifstream in(d / "h.r32", std::ios::binary);
  std::vector<float> raw(37 * 23);
  in.read(reinterpret_cast<char*>(raw.data()), std::streamsize(raw.size() * 4));
  CHECK(raw[5 * 37 + 11] == float(hf.at(11, 5)));
  CHECK(raw.back() == float(hf.at(36, 22)));
  for (const auto& e : fs::directory_iterator(d))
    CHECK(e.path().string().find(".tmp") == std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("erosion map: red erosion, blue deposition, white unchanged", "[exports]") {
  Heightfield hf(4, 2, 1.0, 1.0);
  std::vector<double> change = {0, -0.2, -0.1, 0, 0.1, 0.2, 0, 0};
  fs::path d = tempDir();
  double scale = writeErosionPng(d / "e.png", hf, change);
  CHECK(scale == 0.2);
  int w = 0, h = 0, comp = 0;
  unsigned char* px = stbi_load((d / "e.png").c_str(), &w, &h, &comp, 3);
  REQUIRE(px);
  auto rgb = [&](int v) { return std::array<int, 3>{px[v * 3], px[v * 3 + 1], px[v * 3 + 2]}; };
  CHECK(rgb(0) == std::array<int, 3>{255, 255, 255});
  CHECK(rgb(1) == std::array<int, 3>{255, 0, 0});      // full erosion
  CHECK(rgb(2) == std::array<int, 3>{255, 128, 128});  // half erosion
  CHECK(rgb(5) == std::array<int, 3>{0, 0, 255});      // full deposition
  CHECK(rgb(4) == std::array<int, 3>{128, 128, 255});
  stbi_image_free(px);
  fs::remove_all(d);
}

TEST_CASE("particle PLY carries the sediment concentration", "[exports]") {
  Fluid f;
  f.push(Vec3f(1, 2, 3), Vec3f(4, 5, 6), 0, 1000.0f);
  f.sed[0] = 0.25e-6;
  fs::path d = tempDir();
  writeParticlesPly(d / "p.ply", f, 1e-6, 0.125);
  std::ifstream in(d / "p.ply", std::ios::binary);
  std::string all((std::istreambuf_iterator<char>(in)), {});
  auto end = all.find("end_header\n");
  REQUIRE(end != std::string::npos);
  std::string head = all.substr(0, end);
  CHECK(head.find("comment time_s 0.125") != std::string::npos);
  CHECK(head.find("property float c\n") != std::string::npos);
  float row[7];
  REQUIRE(all.size() == end + 11 + sizeof row);
  std::memcpy(row, all.data() + end + 11, sizeof row);
  CHECK(row[0] == 1.0f);
  CHECK(row[5] == 6.0f);
  CHECK(row[6] == Approx(0.25));
  fs::remove_all(d);
}

TEST_CASE("terrain OBJ: vertices, normals and upward faces", "[exports]") {
  Heightfield hf(5, 4, 0.5, 0.25);
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 5; ++i) hf.at(i, k) = 0.2 * i * 0.5 - 0.4 * k * 0.25;  // a plane
  fs::path d = tempDir();
  writeTerrainObj(d / "m.obj", hf);
  std::ifstream in(d / "m.obj");
  std::vector<Eigen::Vector3d> v, n;
  std::vector<std::array<int, 3>> f;
  for (std::string line; std::getline(in, line);) {
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    if (tag == "v" || tag == "vn") {
      Eigen::Vector3d p;
      s >> p.x() >> p.y() >> p.z();
      (tag == "v" ? v : n).push_back(p);
    } else if (tag == "f") {
      std::array<int, 3> ids;
      for (int& id : ids) {
        std::string tok;
        s >> tok;
        id = std::stoi(tok.substr(0, tok.find('/')));
      }
      f.push_back(ids);
    }
  }
  CHECK(v.size() == 20);
  CHECK(n.size() == 20);
  CHECK(f.size() == size_t(hf.triangleCount()));
  const Eigen::Vector3d plane = Eigen::Vector3d(-0.2, 1.0, 0.4).normalized();
  for (const auto& u : n) CHECK((u - plane).norm() < 1e-6);
  double area = 0;
  for (const auto& t : f) {
    Eigen::Vector3d a = v[size_t(t[0] - 1)], b = v[size_t(t[1] - 1)], c = v[size_t(t[2] - 1)];
    Eigen::Vector3d fn = (b - a).cross(c - a);
    CHECK(fn.y() > 0);  // counter-clockwise seen from above
    area += 0.5 * std::abs(fn.y());
  }
  CHECK(area == Approx(2.0 * 0.75));  // projected area of the grid
  fs::remove_all(d);
}

TEST_CASE("terrain glTF: the grid's vertices, upward faces and the maps as attributes, read back by tinygltf", "[exports]") {
  Heightfield hf(4, 3, 0.5, 0.25, 1.0, -2.0);
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 4; ++i) hf.at(i, k) = 0.1 * i - 0.05 * k;
  TerrainMap wear{"wear", "m", "", std::vector<double>(12), {}};
  TerrainMap dir{"flow_direction", "-", "", std::vector<double>(12, 0.6), std::vector<double>(12, -0.8)};
  for (size_t v = 0; v < 12; ++v) wear.values[v] = 0.001 * double(v);
  const fs::path path = tempDir() / "t.glb";
  CHECK(writeTerrainGltf(path, hf, {wear, dir}) == std::vector<std::string>{"_WEAR", "_FLOW_DIRECTION"});
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  REQUIRE(loader.LoadBinaryFromFile(&m, &err, &warn, path.string()));
  REQUIRE(m.meshes.size() == 1);
  const tinygltf::Primitive& p = m.meshes[0].primitives.at(0);
  auto floats = [&](const std::string& attribute) {
    const tinygltf::Accessor& a = m.accessors[size_t(p.attributes.at(attribute))];
    const tinygltf::BufferView& v = m.bufferViews[size_t(a.bufferView)];
    const size_t per = a.type == TINYGLTF_TYPE_VEC3 ? 3 : a.type == TINYGLTF_TYPE_VEC2 ? 2 : 1;
    std::vector<float> out(a.count * per);
    std::memcpy(out.data(), m.buffers[0].data.data() + v.byteOffset + a.byteOffset, out.size() * sizeof(float));
    return out;
  };
  const std::vector<float> pos = floats("POSITION"), nrm = floats("NORMAL"), uv = floats("TEXCOORD_0");
  REQUIRE(pos.size() == 36);
  // Vertex (i, k) = 2 + 4 k … at (x0 + i dx, h, z0 + k dz), u = i / 3, v = k / 2.
  const size_t v = 2 * 4 + 3;
  CHECK(pos[3 * v] == Approx(1.0 + 3 * 0.5));
  CHECK(pos[3 * v + 1] == Approx(0.3 - 0.1));
  CHECK(pos[3 * v + 2] == Approx(-2.0 + 2 * 0.25));
  CHECK(uv[2 * v] == Approx(1.0));
  CHECK(uv[2 * v + 1] == Approx(1.0));
  for (size_t k = 0; k < 12; ++k) CHECK(nrm[3 * k + 1] > 0.9f);
  const std::vector<float> w = floats("_WEAR"), d = floats("_FLOW_DIRECTION");
  REQUIRE(w.size() == 12);
  CHECK(w[7] == Approx(0.007));
  REQUIRE(d.size() == 24);
  CHECK(d[2 * 5] == Approx(0.6));
  CHECK(d[2 * 5 + 1] == Approx(-0.8));
  // Two triangles a cell, each counter-clockwise seen from above (its normal points up).
  const tinygltf::Accessor& ia = m.accessors[size_t(p.indices)];
  REQUIRE(ia.count == size_t(3 * 2 * 3 * 2));
  const tinygltf::BufferView& iv = m.bufferViews[size_t(ia.bufferView)];
  std::vector<uint32_t> idx(ia.count);
  std::memcpy(idx.data(), m.buffers[0].data.data() + iv.byteOffset + ia.byteOffset, idx.size() * sizeof(uint32_t));
  for (size_t t = 0; t < idx.size(); t += 3) {
    auto at = [&](uint32_t q) { return Eigen::Vector3d(pos[3 * q], pos[3 * q + 1], pos[3 * q + 2]); };
    const Eigen::Vector3d a = at(idx[t]), b = at(idx[t + 1]), c = at(idx[t + 2]);
    CHECK((b - a).cross(c - a).y() > 0);
  }
}
