#include "scene/gltf.h"

#include <Eigen/Geometry>
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "scene/output.h"

namespace scour {

namespace {

// Appends `data` to the model's one buffer as a view and an accessor of `count` elements; returns
// the accessor's index.
template <class T>
int addAccessor(tinygltf::Model& m, const std::vector<T>& data, size_t count, int type, int component, int target,
                std::vector<double> lo = {}, std::vector<double> hi = {}) {
  tinygltf::Buffer& buffer = m.buffers[0];
  while (buffer.data.size() % 4) buffer.data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.data.size();
  view.byteLength = data.size() * sizeof(T);
  view.target = target;
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  buffer.data.insert(buffer.data.end(), bytes, bytes + view.byteLength);
  m.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.bufferView = int(m.bufferViews.size()) - 1;
  a.componentType = component;
  a.count = count;
  a.type = type;
  a.minValues = std::move(lo), a.maxValues = std::move(hi);
  m.accessors.push_back(a);
  return int(m.accessors.size()) - 1;
}

}  // namespace

std::vector<std::string> writeTerrainGltf(const std::filesystem::path& path, const Heightfield& hf,
                                          const std::vector<TerrainMap>& maps) {
  const int nx = hf.nx(), nz = hf.nz();
  const size_t n = size_t(nx) * size_t(nz);
  std::vector<float> position(3 * n), normal(3 * n, 0.0f), uv(2 * n);
  std::vector<double> lo = {1e300, 1e300, 1e300}, hi = {-1e300, -1e300, -1e300};
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const size_t v = size_t(k) * size_t(nx) + size_t(i);
      const float p[3] = {float(hf.x0() + i * hf.dx()), float(hf.at(i, k)), float(hf.z0() + k * hf.dz())};
      for (int c = 0; c < 3; ++c) {
        position[3 * v + size_t(c)] = p[c];
        lo[size_t(c)] = std::min(lo[size_t(c)], double(p[c])), hi[size_t(c)] = std::max(hi[size_t(c)], double(p[c]));
      }
      uv[2 * v] = nx > 1 ? float(i) / float(nx - 1) : 0.0f;
      uv[2 * v + 1] = nz > 1 ? float(k) / float(nz - 1) : 0.0f;
    }
  // The normals as the OBJ writer's: the area-weighted mean of the adjacent triangles'.
  std::vector<Eigen::Vector3d> sum(n, Eigen::Vector3d::Zero());
  std::vector<uint32_t> index;
  index.reserve(size_t(hf.triangleCount()) * 3);
  for (int t = 0; t < hf.triangleCount(); ++t) {
    const auto c = hf.triangleCorners(t);
    const Eigen::Vector3d nrm = (c[2] - c[0]).cross(c[1] - c[0]);  // pointing up
    const auto idx = hf.triangleVertexIndices(t);
    for (size_t v : idx) sum[v] += nrm;
    // Counter-clockwise seen from above (glTF's front faces): the order whose normal points up.
    index.push_back(uint32_t(idx[0])), index.push_back(uint32_t(idx[2])), index.push_back(uint32_t(idx[1]));
  }
  for (size_t v = 0; v < n; ++v) {
    const Eigen::Vector3d u = sum[v].norm() > 0 ? sum[v].normalized() : Eigen::Vector3d(0, 1, 0);
    for (int c = 0; c < 3; ++c) normal[3 * v + size_t(c)] = float(u[c]);
  }
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "Scour";
  m.buffers.resize(1);
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = addAccessor(m, position, n, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                            TINYGLTF_TARGET_ARRAY_BUFFER, lo, hi);
  prim.attributes["NORMAL"] = addAccessor(m, normal, n, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.attributes["TEXCOORD_0"] = addAccessor(m, uv, n, TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
  std::vector<std::string> names;
  for (const TerrainMap& map : maps) {
    if (map.values.size() != n) throw std::runtime_error("cannot write " + path.string() + ": map " + map.name + " does not fit the grid");
    std::string name = "_" + map.name;
    for (char& c : name) c = char(std::toupper(static_cast<unsigned char>(c)));
    std::vector<float> values;
    if (map.second.empty()) {
      values.assign(map.values.begin(), map.values.end());
      prim.attributes[name] = addAccessor(m, values, n, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
    } else {
      values.resize(2 * n);
      for (size_t v = 0; v < n; ++v) values[2 * v] = float(map.values[v]), values[2 * v + 1] = float(map.second[v]);
      prim.attributes[name] = addAccessor(m, values, n, TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
    }
    names.push_back(name);
  }
  prim.indices = addAccessor(m, index, index.size(), TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                             TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  m.buffers[0].data.resize((m.buffers[0].data.size() + 3) / 4 * 4, 0);
  tinygltf::Mesh mesh;
  mesh.name = "terrain";
  mesh.primitives.push_back(prim);
  m.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = "terrain";
  m.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  std::ostringstream bytes;
  tinygltf::TinyGLTF gltf;
  if (!gltf.WriteGltfSceneToStream(&m, bytes, false, true))
    throw std::runtime_error("cannot write " + path.string() + ": tinygltf could not write the mesh");
  const std::string data = bytes.str();
  writeAtomically(path, [&](std::ostream& out) { out << data; });
  return names;
}

}  // namespace scour
