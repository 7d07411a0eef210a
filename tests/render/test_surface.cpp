// The GPU water surface (paper §5) on llvmpipe, headless: marching tetrahedra on the GPU equals
// the CPU reference on the same density grid; the occupancy grid changes nothing but the work; a
// ball of particles gives a closed surface enclosing the particles' volume; EGL and OSMesa agree;
// and no GL error is raised anywhere.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <map>

#include "engine/params.h"
#include "render/context.h"
#include "render/mt_reference.h"
#include "render/surface.h"

using namespace scour;

namespace {

// Particles on a cubic lattice of spacing ds inside a ball of radius r around c.
Frame ball(double ds, double r, Eigen::Vector3f c = {0.3f, 0.4f, 0.5f}) {
  SimParams p;
  p.spacing = ds;
  Frame f;
  f.spacing = float(ds);
  f.support = float(p.support());
  f.mass = float(p.particleMass());
  f.rest_density = float(p.rest_density);
  const int n = int(std::ceil(r / ds));
  for (int k = -n; k <= n; ++k)
    for (int j = -n; j <= n; ++j)
      for (int i = -n; i <= n; ++i) {
        Eigen::Vector3f x = ds * Eigen::Vector3f(i + 0.5f, j + 0.5f, k + 0.5f);
        if (x.norm() <= r) f.position.push_back(c + x);
      }
  return f;
}

// Two blobs and a thin sheet: several components, flat and curved parts.
Frame scene() {
  Frame f = ball(0.02, 0.1);
  Frame g = ball(0.02, 0.06, {0.6f, 0.35f, 0.45f});
  f.position.insert(f.position.end(), g.position.begin(), g.position.end());
  for (int i = 0; i < 20; ++i)
    for (int k = 0; k < 20; ++k)
      for (int j = 0; j < 2; ++j) f.position.push_back({0.01f + 0.02f * i, 0.05f + 0.02f * j, 0.8f + 0.02f * k});
  return f;
}

// Triangles as a sorted list of vertex positions rotated so the smallest comes first: the
// GPU's append order does not matter.
std::vector<std::array<float, 9>> canonical(const std::vector<SurfaceTriangle>& t) {
  std::vector<std::array<float, 9>> out;
  for (const auto& tri : t) {
    int first = 0;
    auto key = [&](int k) { const auto& p = tri[size_t(k)].position; return std::array<float, 3>{p.x(), p.y(), p.z()}; };
    for (int k = 1; k < 3; ++k)
      if (key(k) < key(first)) first = k;
    std::array<float, 9> a{};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) a[size_t(3 * k + d)] = tri[size_t((first + k) % 3)].position[d];
    out.push_back(a);
  }
  std::sort(out.begin(), out.end());
  return out;
}

GlContext& egl() {
  static std::unique_ptr<GlContext> c = createGlContext(GlBackend::kEgl);
  c->makeCurrent();
  return *c;
}

}  // namespace

TEST_CASE("GPU marching tetrahedra equals the CPU reference", "[render][surface]") {
  GlContext& gl = egl();
  gl.resetErrors();
  WaterSurface surface;
  const Frame f = scene();
  surface.update(f);
  const auto gpu = canonical(surface.readTriangles());
  const DensityGrid grid = surface.readDensity();
  const auto cpu = canonical(marchTetrahedraCpu(grid, surface.settings().iso));
  REQUIRE(gpu.size() > 1000);
  REQUIRE(gpu.size() == cpu.size());
  double worst = 0;
  for (size_t t = 0; t < gpu.size(); ++t)
    for (size_t k = 0; k < 9; ++k) worst = std::max(worst, double(std::abs(gpu[t][k] - cpu[t][k])));
  CHECK(worst <= 1e-4 * grid.cell);
  CHECK(surface.readStats().dropped == 0);
  CHECK(gl.errors() == 0);
  INFO(gl.lastError());
}

TEST_CASE("the occupancy grid changes nothing in the mesh and visits fewer cells", "[render][surface]") {
  GlContext& gl = egl();
  gl.resetErrors();
  const Frame f = scene();
  SurfaceSettings s;
  WaterSurface with(s);
  with.update(f);
  s.occupancy = false;
  WaterSurface without(s);
  without.update(f);
  const SurfaceStats a = with.readStats(), b = without.readStats();
  CHECK(canonical(with.readTriangles()) == canonical(without.readTriangles()));
  CHECK(a.occupied < a.blocks);
  CHECK(b.occupied == b.blocks);
  // The same iso-cubes are found either way, and the mesh was left as it was.
  const long cubesWith = with.countIsoCubes(nullptr), cubesWithout = without.countIsoCubes(nullptr);
  CHECK(cubesWith > 0);
  CHECK(cubesWith == cubesWithout);
  CHECK(with.readStats().triangles == a.triangles);
  std::printf("occupancy grid: %ld of %ld blocks visited (%.1f%%), %ld triangles either way\n",
              a.occupied, a.blocks, 100.0 * double(a.occupied) / double(a.blocks), a.triangles);
  CHECK(gl.errors() == 0);
}

TEST_CASE("a ball of particles gives a closed surface around its volume", "[render][surface]") {
  GlContext& gl = egl();
  gl.resetErrors();
  const Frame f = ball(0.02, 0.15);
  WaterSurface surface;
  surface.update(f);
  const auto tris = surface.readTriangles();
  REQUIRE(tris.size() > 1000);
  // Weld exactly equal positions (both cells of an edge compute the same point bit for bit) and
  // count how often each undirected edge is used: a closed surface uses each exactly twice.
  std::map<std::array<float, 3>, int> ids;
  auto id = [&](const Eigen::Vector3f& p) {
    auto [it, fresh] = ids.emplace(std::array<float, 3>{p.x(), p.y(), p.z()}, int(ids.size()));
    return it->second;
  };
  std::map<std::pair<int, int>, int> edges;
  double volume = 0;
  long degenerate = 0;
  for (const auto& t : tris) {
    const int a = id(t[0].position), b = id(t[1].position), c = id(t[2].position);
    if (a == b || b == c || a == c) {
      ++degenerate;
      continue;
    }
    for (auto [u, v] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) ++edges[{std::min(u, v), std::max(u, v)}];
    // Divergence theorem: outward-facing triangles give a positive enclosed volume.
    volume += double(t[0].position.dot(t[1].position.cross(t[2].position))) / 6.0;
  }
  CHECK(degenerate == 0);
  long open = 0;
  for (const auto& [e, uses] : edges) open += uses != 2;
  CHECK(open == 0);
  const double particlesVolume = double(f.particles()) * f.mass / f.rest_density;
  std::printf("ball: %zu particles, volume %.6f m³, surface encloses %.6f m³ (%+.1f%%)\n",
              f.particles(), particlesVolume, volume, 100 * (volume / particlesVolume - 1));
  CHECK(volume == Approx(particlesVolume).epsilon(0.10));
  // Normals from the density gradient point out of the water.
  long inward = 0;
  for (const auto& t : tris)
    for (const auto& v : t) inward += v.normal.dot(v.position - Eigen::Vector3f(0.3f, 0.4f, 0.5f)) < 0;
  CHECK(inward == 0);
  CHECK(gl.errors() == 0);
}

TEST_CASE("EGL and OSMesa extract the same surface", "[render][surface]") {
  const Frame f = scene();
  std::vector<std::array<float, 9>> mesh[2];
  int k = 0;
  for (GlBackend b : {GlBackend::kEgl, GlBackend::kOsMesa}) {
    INFO(glBackendName(b));
    auto ctx = b == GlBackend::kEgl ? nullptr : createGlContext(b);
    GlContext& gl = ctx ? *ctx : egl();
    gl.resetErrors();
    CHECK_THAT(gl.version(), Catch::StartsWith("4.5"));
    WaterSurface s;
    s.update(f);
    mesh[k++] = canonical(s.readTriangles());
    CHECK(gl.errors() == 0);
  }
  CHECK(mesh[0] == mesh[1]);
}

TEST_CASE("a GL error is counted by the debug callback", "[render]") {
  GlContext& gl = egl();
  gl.resetErrors();
  glBindBuffer(GL_ARRAY_BUFFER, 123456);  // not a buffer name: GL_INVALID_OPERATION
  CHECK(gl.errors() == 1);
  CHECK_FALSE(gl.lastError().empty());
  gl.resetErrors();
}
