#include "render/surface.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace scour {

namespace {
constexpr GLuint kRow = 32768;  // work groups per dispatch row (finish.glsl, march.glsl)

void grow(GLuint& buffer, size_t& capacity, size_t needed, size_t elementBytes) {
  if (buffer && needed <= capacity) return;
  capacity = std::max(needed, capacity + capacity / 2);
  if (!buffer) glCreateBuffers(1, &buffer);
  glNamedBufferData(buffer, GLsizeiptr(capacity * elementBytes), nullptr, GL_DYNAMIC_DRAW);
}
}  // namespace

WaterSurface::WaterSurface(SurfaceSettings s)
    : s_(s),
      splat_(Program::compute("splat")),
      compact_(Program::compute("compact")),
      finish_(Program::compute("finish")),
      march_(Program::compute("march")) {
  glCreateBuffers(1, &draw_);
  const GLuint empty[6] = {0, 1, 0, 0, 0, 0};
  glNamedBufferData(draw_, sizeof empty, empty, GL_DYNAMIC_DRAW);
}

WaterSurface::~WaterSurface() {
  GLuint buffers[] = {particles_, density_, occupancy_, list_, vertices_, draw_};
  for (GLuint b : buffers)
    if (b) glDeleteBuffers(1, &b);
}

void WaterSurface::layout(const Frame& f) {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(INFINITY), hi = -lo;
  for (const auto& p : f.position) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  DensityGrid g;
  g.cell = float(s_.cell_over_spacing * f.spacing);
  for (int attempt = 0; attempt < 64; ++attempt) {
    // The water's box, grown by h (the density reaches that far) and one cell (so the surface
    // closes inside the grid), on whole multiples of the cell.
    const float margin = f.support + g.cell;
    Eigen::Vector3f a = ((lo.array() - margin) / g.cell).floor() * g.cell;
    Eigen::Vector3f b = hi.array() + margin;
    Eigen::Vector3i cells = ((b - a) / g.cell).array().ceil().cast<int>().cwiseMax(1);
    g.origin = a;
    g.blocks = (cells.array() + 3) / 4;
    g.nodes = g.blocks * 4 + Eigen::Vector3i::Ones();
    if (g.nodeCount() <= s_.max_nodes) break;
    g.cell *= float(std::cbrt(double(g.nodeCount()) / double(s_.max_nodes)) * 1.01);
  }
  grid_ = g;
}

void WaterSurface::update(const Frame& f) {
  const GLuint emptyDraw[6] = {0, 1, 0, 0, 0, 0};
  glNamedBufferSubData(draw_, 0, sizeof emptyDraw, emptyDraw);
  wall_[0] = wall_[1] = wall_[2] = 0;
  if (f.particles() == 0) {
    grid_ = DensityGrid{};
    return;
  }
  layout(f);
  const size_t n = f.particles();
  grow(particles_, particleCap_, n, 4 * sizeof(float));
  std::vector<float> packed(4 * n);
  for (size_t i = 0; i < n; ++i) {
    packed[4 * i] = f.position[i].x(), packed[4 * i + 1] = f.position[i].y();
    packed[4 * i + 2] = f.position[i].z(), packed[4 * i + 3] = 1.0f;
  }
  glNamedBufferSubData(particles_, 0, GLsizeiptr(packed.size() * sizeof(float)), packed.data());
  grow(density_, nodeCap_, grid_.nodeCount(), sizeof(GLuint));
  grow(occupancy_, blockCap_, grid_.blockCount(), sizeof(GLuint));
  grow(list_, listCap_, grid_.blockCount() + 4, sizeof(GLuint));
  GLuint zero = 0;
  glClearNamedBufferSubData(density_, GL_R32UI, 0, GLsizeiptr(grid_.nodeCount() * sizeof(GLuint)),
                            GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glClearNamedBufferSubData(occupancy_, GL_R32UI, 0, GLsizeiptr(grid_.blockCount() * sizeof(GLuint)),
                            GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  const GLuint header[4] = {0, 0, 1, 1};
  glNamedBufferSubData(list_, 0, sizeof header, header);
  // The vertex buffer: 8 triangles per particle covers a pool a few particles deep (a flat
  // surface cut into tetrahedra gives about 8 per cell); growIfOverflowed corrects the rest.
  const size_t want = std::min(s_.max_triangles, std::max<size_t>(65536, 8 * n)) * 3;
  grow(vertices_, vertexCap_, want, 8 * sizeof(float));

  // 1. splat (and mark the occupied blocks)
  const double h = f.support;
  const double poly6 = 315.0 / (64.0 * M_PI * std::pow(h, 9));
  splat_.use();
  glUniform1ui(splat_.location("count"), GLuint(n));
  glUniform3f(splat_.location("origin"), grid_.origin.x(), grid_.origin.y(), grid_.origin.z());
  glUniform1f(splat_.location("cell"), grid_.cell);
  glUniform3i(splat_.location("nodes"), grid_.nodes.x(), grid_.nodes.y(), grid_.nodes.z());
  glUniform3i(splat_.location("blocks"), grid_.blocks.x(), grid_.blocks.y(), grid_.blocks.z());
  glUniform1f(splat_.location("h"), float(h));
  glUniform1f(splat_.location("weight"), float(f.mass * poly6 / f.rest_density * grid_.scale));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, particles_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, density_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, occupancy_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, list_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, vertices_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, draw_);
  using Clock = std::chrono::steady_clock;
  auto mark = Clock::now();
  auto lap = [&](int k) {
    if (!s_.profile) return;
    glFinish();
    const auto now = Clock::now();
    wall_[k] = std::chrono::duration<double>(now - mark).count();
    mark = now;
  };
  if (s_.profile) glFinish(), mark = Clock::now();
  glDispatchCompute(GLuint((n + 127) / 128), 1, 1);
  lap(0);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  // 2. list the occupied blocks
  if (s_.occupancy) {
    compact_.use();
    glUniform1ui(compact_.location("blockCount"), GLuint(grid_.blockCount()));
    glDispatchCompute(GLuint((grid_.blockCount() + 255) / 256), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    finish_.use();
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  }
  lap(1);

  // 3. march
  march();
  lap(2);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT |
                  GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void WaterSurface::march(bool countOnly) {
  march_.use();
  glUniform3f(march_.location("origin"), grid_.origin.x(), grid_.origin.y(), grid_.origin.z());
  glUniform1f(march_.location("cell"), grid_.cell);
  glUniform3i(march_.location("nodes"), grid_.nodes.x(), grid_.nodes.y(), grid_.nodes.z());
  glUniform3i(march_.location("blocks"), grid_.blocks.x(), grid_.blocks.y(), grid_.blocks.z());
  glUniform1f(march_.location("iso"), float(s_.iso * grid_.scale));
  glUniform1ui(march_.location("maxVertices"), GLuint(vertexCap_));
  glUniform1i(march_.location("useList"), s_.occupancy ? 1 : 0);
  glUniform1ui(march_.location("blockCount"), GLuint(grid_.blockCount()));
  glUniform1i(march_.location("countOnly"), countOnly ? 1 : 0);
  if (s_.occupancy) {
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, list_);
    glDispatchComputeIndirect(sizeof(GLuint));  // after the count
  } else {
    const GLuint nb = GLuint(grid_.blockCount());
    glDispatchCompute(std::min(nb, kRow), (nb + kRow - 1) / kRow, 1);
  }
}

long WaterSurface::countIsoCubes(double* seconds) {
  if (grid_.blockCount() == 0) return 0;
  // The same inputs as the last update's march; only the iso-cube counter changes.
  const GLuint zero = 0;
  glNamedBufferSubData(draw_, 5 * sizeof(GLuint), sizeof zero, &zero);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, density_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, list_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, vertices_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, draw_);
  glFinish();
  const auto t0 = std::chrono::steady_clock::now();
  march(true);
  glFinish();
  if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  GLuint count = 0;
  glGetNamedBufferSubData(draw_, 5 * sizeof(GLuint), sizeof count, &count);
  return long(count);
}

bool WaterSurface::growIfOverflowed() {
  const SurfaceStats st = readStats();
  if (st.dropped == 0 || vertexCap_ >= s_.max_triangles * 3) return false;
  const size_t want = std::min(s_.max_triangles, size_t(double(st.triangles + st.dropped) * 1.25)) * 3;
  grow(vertices_, vertexCap_, want, 8 * sizeof(float));
  return true;
}

WaterSurface::Timings WaterSurface::readTimings() const {
  Timings t;
  t.splat = wall_[0], t.occupancy = wall_[1], t.march = wall_[2];
  return t;
}

DensityGrid WaterSurface::readDensity() const {
  DensityGrid g = grid_;
  g.value.resize(g.nodeCount());
  if (!g.value.empty())
    glGetNamedBufferSubData(density_, 0, GLsizeiptr(g.value.size() * sizeof(GLuint)), g.value.data());
  return g;
}

SurfaceStats WaterSurface::readStats() const {
  SurfaceStats s;
  GLuint draw[5] = {0, 0, 0, 0, 0};
  glGetNamedBufferSubData(draw_, 0, sizeof draw, draw);
  s.triangles = long(draw[0] / 3);
  s.dropped = long(draw[4]);
  s.blocks = long(grid_.blockCount());
  if (s_.occupancy && list_ && s.blocks > 0) {
    GLuint count = 0;
    glGetNamedBufferSubData(list_, 0, sizeof count, &count);
    s.occupied = long(count);
  } else {
    s.occupied = s.blocks;
  }
  return s;
}

std::vector<SurfaceTriangle> WaterSurface::readTriangles() const {
  const SurfaceStats st = readStats();
  std::vector<float> raw(size_t(st.triangles) * 3 * 8);
  if (!raw.empty())
    glGetNamedBufferSubData(vertices_, 0, GLsizeiptr(raw.size() * sizeof(float)), raw.data());
  std::vector<SurfaceTriangle> out(size_t(st.triangles));
  for (size_t t = 0; t < out.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const float* v = &raw[(3 * t + size_t(k)) * 8];
      out[t][size_t(k)].position = {v[0], v[1], v[2]};
      out[t][size_t(k)].normal = {v[4], v[5], v[6]};
    }
  return out;
}

}  // namespace scour
