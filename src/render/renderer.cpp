#include "render/renderer.h"

#include <stb_image_write.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "render/context.h"
#include "scene/output.h"

namespace scour {

namespace {

// GL's rows run bottom-up; pictures are written top row first.
std::vector<unsigned char> topRowFirst(const std::vector<unsigned char>& rgba, int width,
                                       int height) {
  std::vector<unsigned char> rows(rgba.size());
  const size_t row = size_t(width) * 4;
  for (int r = 0; r < height; ++r)
    std::copy_n(rgba.begin() + long(size_t(height - 1 - r) * row), row,
                rows.begin() + long(size_t(r) * row));
  return rows;
}

// A sprite's size in pixels at distance 1: one particle spacing across.
float spritePixels(const Frame& f, const Camera& c, int height) {
  return float(height) * f.spacing / (2 * std::tan(0.5f * c.fov_deg * float(M_PI) / 180));
}

Eigen::Matrix4f lookAt(const Eigen::Vector3f& eye, const Eigen::Vector3f& target, const Eigen::Vector3f& up) {
  const Eigen::Vector3f f = (target - eye).normalized();
  const Eigen::Vector3f s = f.cross(up).normalized();
  const Eigen::Vector3f u = s.cross(f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye), m(1, 3) = -u.dot(eye), m(2, 3) = f.dot(eye);
  return m;
}

Eigen::Matrix4f ortho(float l, float r, float b, float t, float n, float f) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m(0, 0) = 2 / (r - l), m(1, 1) = 2 / (t - b), m(2, 2) = -2 / (f - n);
  m(0, 3) = -(r + l) / (r - l), m(1, 3) = -(t + b) / (t - b), m(2, 3) = -(f + n) / (f - n);
  return m;
}

GLuint texture2D(GLenum format, int w, int h, GLenum filter) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, 1, format, w, h);
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GLint(filter));
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GLint(filter));
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

void deleteTextures(std::initializer_list<GLuint*> ts) {
  for (GLuint* t : ts)
    if (*t) glDeleteTextures(1, t), *t = 0;
}

void deleteFramebuffers(std::initializer_list<GLuint*> fs) {
  for (GLuint* f : fs)
    if (*f) glDeleteFramebuffers(1, f), *f = 0;
}

// A framebuffer with these (attachment point, texture) pairs, checked complete.
GLuint framebuffer(std::initializer_list<std::pair<GLenum, GLuint>> attachments, const char* what) {
  GLuint f = 0;
  glCreateFramebuffers(1, &f);
  for (const auto& [point, texture] : attachments) glNamedFramebufferTexture(f, point, texture, 0);
  if (glCheckNamedFramebufferStatus(f, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw GlError(std::string("renderer: incomplete ") + what + " framebuffer");
  return f;
}

void setMatrix(const Program& p, const char* name, const Eigen::Matrix4f& m) {
  glProgramUniformMatrix4fv(p.id(), p.location(name), 1, GL_FALSE, m.data());
}

}  // namespace

Eigen::Matrix4f Camera::cameraFromWorld() const { return lookAt(eye, target, up); }

Eigen::Matrix4f Camera::clipFromCamera(float aspect, float near, float far) const {
  const float f = 1.0f / std::tan(0.5f * fov_deg * float(M_PI) / 180.0f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  m(0, 0) = f / aspect, m(1, 1) = f;
  m(2, 2) = (far + near) / (near - far), m(2, 3) = 2 * far * near / (near - far);
  m(3, 2) = -1;
  return m;
}

Camera overviewCamera(const Frame& f) {
  const float lx = float(f.dx * (f.nx - 1)), lz = float(f.dz * (f.nz - 1));
  float lo = 0, hi = 0;
  if (!f.height.empty()) {
    auto [a, b] = std::minmax_element(f.height.begin(), f.height.end());
    lo = *a, hi = *b;
  }
  Camera c;
  c.target = {float(f.x0) + 0.5f * lx, lo + 0.3f * (hi - lo), float(f.z0) + 0.5f * lz};
  const float size = std::max(lx, lz);
  c.eye = c.target + 1.2f * Eigen::Vector3f(-0.45f * lx, 0.75f * size + (hi - lo), 0.95f * lz);
  return c;
}

Renderer::Renderer(int width, int height)
    : width_(width),
      height_(height),
      terrain_(Program::graphics("terrain_vs", "terrain_fs")),
      water_(Program::graphics("water_vs", "water_fs")),
      lightTerrain_(Program::graphics("terrain_vs", "light_terrain_fs")),
      lightWater_(Program::graphics("water_vs", "light_water_fs")),
      photon_(Program::graphics("photon_vs", "photon_fs")),
      particles_(Program::graphics("particles_vs", "particles_fs")),
      spray_(Program::graphics("spray_vs", "spray_fs")) {
  glCreateVertexArrays(1, &emptyVao_);
  // The water VAO reads the surface's vertex buffer: vec4 position, vec4 normal.
  glCreateVertexArrays(1, &waterVao_);
  for (GLuint a : {0u, 1u}) {
    glEnableVertexArrayAttrib(waterVao_, a);
    glVertexArrayAttribFormat(waterVao_, a, 4, GL_FLOAT, GL_FALSE, a * 16);
    glVertexArrayAttribBinding(waterVao_, a, 0);
  }
  glCreateVertexArrays(1, &particleVao_);
  glEnableVertexArrayAttrib(particleVao_, 0);
  glVertexArrayAttribFormat(particleVao_, 0, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(particleVao_, 0, 0);
  makeTargets();
  makeSky();
}

Renderer::~Renderer() {
  deleteTextures({&heights_, &change_, &map_, &map2_, &backColour_, &backDepth_, &finalColour_, &finalDepth_, &receiver_,
                  &receiverDepth_, &waterPos_, &waterNormal_, &waterLightDepth_, &caustic_, &sky_});
  deleteFramebuffers({&backFbo_, &finalFbo_, &receiverFbo_, &waterLightFbo_, &causticFbo_});
  for (GLuint* v : {&emptyVao_, &waterVao_, &particleVao_})
    if (*v) glDeleteVertexArrays(1, v);
  if (particleBuffer_) glDeleteBuffers(1, &particleBuffer_);
}

void Renderer::makeTargets() {
  deleteTextures({&backColour_, &backDepth_, &finalColour_, &finalDepth_});
  deleteFramebuffers({&backFbo_, &finalFbo_});
  backColour_ = texture2D(GL_RGBA8, width_, height_, GL_LINEAR);
  backDepth_ = texture2D(GL_DEPTH_COMPONENT32F, width_, height_, GL_NEAREST);
  finalColour_ = texture2D(GL_RGBA8, width_, height_, GL_LINEAR);
  finalDepth_ = texture2D(GL_DEPTH_COMPONENT32F, width_, height_, GL_NEAREST);
  backFbo_ = framebuffer({{GL_COLOR_ATTACHMENT0, backColour_}, {GL_DEPTH_ATTACHMENT, backDepth_}},
                         "terrain");
  finalFbo_ = framebuffer({{GL_COLOR_ATTACHMENT0, finalColour_}, {GL_DEPTH_ATTACHMENT, finalDepth_}},
                          "picture");
}

void Renderer::makeLightTargets(int size) {
  if (size == lightSize_) return;
  lightSize_ = size;
  deleteTextures({&receiver_, &receiverDepth_, &waterPos_, &waterNormal_, &waterLightDepth_, &caustic_});
  deleteFramebuffers({&receiverFbo_, &waterLightFbo_, &causticFbo_});
  receiver_ = texture2D(GL_RGBA32F, size, size, GL_NEAREST);
  receiverDepth_ = texture2D(GL_DEPTH_COMPONENT32F, size, size, GL_NEAREST);
  waterPos_ = texture2D(GL_RGBA32F, size, size, GL_NEAREST);
  waterNormal_ = texture2D(GL_RGBA16F, size, size, GL_NEAREST);
  waterLightDepth_ = texture2D(GL_DEPTH_COMPONENT32F, size, size, GL_NEAREST);
  caustic_ = texture2D(GL_R32F, size, size, GL_LINEAR);
  receiverFbo_ = framebuffer(
      {{GL_COLOR_ATTACHMENT0, receiver_}, {GL_DEPTH_ATTACHMENT, receiverDepth_}}, "receiver");
  waterLightFbo_ = framebuffer({{GL_COLOR_ATTACHMENT0, waterPos_},
                                {GL_COLOR_ATTACHMENT1, waterNormal_},
                                {GL_DEPTH_ATTACHMENT, waterLightDepth_}},
                               "water-from-the-sun");
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(waterLightFbo_, 2, both);
  causticFbo_ = framebuffer({{GL_COLOR_ATTACHMENT0, caustic_}}, "caustics");
}

void Renderer::makeSky() {
  // A sky made here: zenith blue to a pale horizon, a warm sun, brown ground below the horizon.
  constexpr int n = 64;
  glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &sky_);
  glTextureStorage2D(sky_, 1, GL_RGBA8, n, n);
  glTextureParameteri(sky_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(sky_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  const Eigen::Vector3f sun = Eigen::Vector3f(0.35f, 1.0f, 0.25f).normalized();
  std::vector<unsigned char> face(size_t(n) * n * 4);
  for (int f = 0; f < 6; ++f) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const float a = 2 * (i + 0.5f) / n - 1, b = 2 * (j + 0.5f) / n - 1;
        Eigen::Vector3f d;  // the cube map convention: +X, −X, +Y, −Y, +Z, −Z
        switch (f) {
          case 0: d = {1, -b, -a}; break;
          case 1: d = {-1, -b, a}; break;
          case 2: d = {a, 1, b}; break;
          case 3: d = {a, -1, -b}; break;
          case 4: d = {a, -b, 1}; break;
          default: d = {-a, -b, -1}; break;
        }
        d.normalize();
        Eigen::Vector3f c;
        if (d.y() >= 0) {
          const float t = std::pow(d.y(), 0.5f);
          c = (1 - t) * Eigen::Vector3f(0.85f, 0.90f, 0.95f) + t * Eigen::Vector3f(0.25f, 0.45f, 0.80f);
        } else {
          c = Eigen::Vector3f(0.40f, 0.34f, 0.28f);
        }
        c += Eigen::Vector3f(1.0f, 0.9f, 0.7f) * std::pow(std::max(d.dot(sun), 0.0f), 400.0f);
        for (int k = 0; k < 3; ++k) face[size_t(4 * (j * n + i) + k)] = (unsigned char)(255 * std::min(c[k], 1.0f));
        face[size_t(4 * (j * n + i) + 3)] = 255;
      }
    glTextureSubImage3D(sky_, 0, 0, 0, f, n, n, 1, GL_RGBA, GL_UNSIGNED_BYTE, face.data());
  }
}

void Renderer::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  width_ = width, height_ = height;
  makeTargets();
}

void Renderer::uploadTerrain(const Frame& f) {
  if (f.nx != terrainNx_ || f.nz != terrainNz_) {
    deleteTextures({&heights_, &change_, &map_, &map2_});
    heights_ = texture2D(GL_R32F, f.nx, f.nz, GL_NEAREST);
    change_ = texture2D(GL_R32F, f.nx, f.nz, GL_NEAREST);
    map_ = texture2D(GL_R32F, f.nx, f.nz, GL_NEAREST);
    map2_ = texture2D(GL_R32F, f.nx, f.nz, GL_NEAREST);
    terrainNx_ = f.nx, terrainNz_ = f.nz;
  }
  glTextureSubImage2D(heights_, 0, 0, 0, f.nx, f.nz, GL_RED, GL_FLOAT, f.height.data());
  if (f.change.size() == f.height.size())
    glTextureSubImage2D(change_, 0, 0, 0, f.nx, f.nz, GL_RED, GL_FLOAT, f.change.data());
  auto [lo, hi] = std::minmax_element(f.height.begin(), f.height.end());
  heightMin_ = *lo, heightMax_ = *hi;
  changeMax_ = 0;
  for (float c : f.change) changeMax_ = std::max(changeMax_, std::abs(c));
  // The erosion map, when the frame has one (zeros otherwise, cleared on the GL side).
  const bool hasMap = f.map.size() == f.height.size();
  mapPair_ = hasMap && f.map2.size() == f.height.size();
  if (hasMap) glTextureSubImage2D(map_, 0, 0, 0, f.nx, f.nz, GL_RED, GL_FLOAT, f.map.data());
  else glClearTexImage(map_, 0, GL_RED, GL_FLOAT, nullptr);
  if (mapPair_) glTextureSubImage2D(map2_, 0, 0, 0, f.nx, f.nz, GL_RED, GL_FLOAT, f.map2.data());
  else glClearTexImage(map2_, 0, GL_RED, GL_FLOAT, nullptr);
  mapMax_ = 0;
  if (hasMap)
    for (float v : f.map) mapMax_ = std::max(mapMax_, std::abs(v));
}

void Renderer::drawTerrain(const Program& p, const Eigen::Matrix4f& clipFromWorld) const {
  p.use();
  glBindTextureUnit(0, heights_);
  glProgramUniform1i(p.id(), p.location("heights"), 0);
  glProgramUniform2i(p.id(), p.location("size"), terrainNx_, terrainNz_);
  setMatrix(p, "clipFromWorld", clipFromWorld);
  glBindVertexArray(emptyVao_);
  glDrawArrays(GL_TRIANGLES, 0, 6 * (terrainNx_ - 1) * (terrainNz_ - 1));
}

void Renderer::drawWater() const {
  glBindVertexArray(waterVao_);
  glVertexArrayVertexBuffer(waterVao_, 0, surface_.vertexBuffer(), 0, 32);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, surface_.drawBuffer());
  glDrawArraysIndirect(GL_TRIANGLES, nullptr);
}

void Renderer::lightPass(const Frame& f, const RenderSettings& s, const Eigen::Matrix4f& lightClipFromWorld) {
  makeLightTargets(s.caustic_map);
  glViewport(0, 0, lightSize_, lightSize_);
  glEnable(GL_DEPTH_TEST);
  // The receiver: terrain positions seen from the sun.
  const float far[4] = {0, -1e9f, 0, 0};
  glClearNamedFramebufferfv(receiverFbo_, GL_COLOR, 0, far);
  const float one = 1.0f;
  glClearNamedFramebufferfv(receiverFbo_, GL_DEPTH, 0, &one);
  glBindFramebuffer(GL_FRAMEBUFFER, receiverFbo_);
  glProgramUniform2f(lightTerrain_.id(), lightTerrain_.location("origin"), float(f.x0), float(f.z0));
  glProgramUniform2f(lightTerrain_.id(), lightTerrain_.location("spacing"), float(f.dx), float(f.dz));
  drawTerrain(lightTerrain_, lightClipFromWorld);
  // The water surface seen from the sun: position (w = 1 where water) and normal.
  const float none[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(waterLightFbo_, GL_COLOR, 0, none);
  glClearNamedFramebufferfv(waterLightFbo_, GL_COLOR, 1, none);
  glClearNamedFramebufferfv(waterLightFbo_, GL_DEPTH, 0, &one);
  glBindFramebuffer(GL_FRAMEBUFFER, waterLightFbo_);
  lightWater_.use();
  setMatrix(lightWater_, "clipFromWorld", lightClipFromWorld);
  drawWater();
  // Photons: one per texel of that map, refracted and splatted where they land.
  glClearNamedFramebufferfv(causticFbo_, GL_COLOR, 0, none);
  glBindFramebuffer(GL_FRAMEBUFFER, causticFbo_);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glEnable(GL_PROGRAM_POINT_SIZE);
  photon_.use();
  glBindTextureUnit(0, waterPos_);
  glBindTextureUnit(1, waterNormal_);
  glBindTextureUnit(2, receiver_);
  glProgramUniform1i(photon_.id(), photon_.location("waterPosition"), 0);
  glProgramUniform1i(photon_.id(), photon_.location("waterNormal"), 1);
  glProgramUniform1i(photon_.id(), photon_.location("receiver"), 2);
  glProgramUniform2i(photon_.id(), photon_.location("mapSize"), lightSize_, lightSize_);
  setMatrix(photon_, "lightClipFromWorld", lightClipFromWorld);
  const Eigen::Vector3f sun = s.sun.normalized();
  glProgramUniform3f(photon_.id(), photon_.location("sunDir"), sun.x(), sun.y(), sun.z());
  glBindVertexArray(emptyVao_);
  glDrawArrays(GL_POINTS, 0, lightSize_ * lightSize_);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
}

template <class Value>
void Renderer::uploadParticles(const Frame& f, Value value) {
  std::vector<float> packed(4 * f.particles());
  for (size_t i = 0; i < f.particles(); ++i) {
    for (int k = 0; k < 3; ++k) packed[4 * i + size_t(k)] = f.position[i][k];
    packed[4 * i + 3] = value(i);
  }
  if (!particleBuffer_ || particleCap_ < packed.size()) {
    if (particleBuffer_) glDeleteBuffers(1, &particleBuffer_);
    glCreateBuffers(1, &particleBuffer_);
    particleCap_ = packed.size();
    glNamedBufferData(particleBuffer_, GLsizeiptr(particleCap_ * sizeof(float)), nullptr, GL_DYNAMIC_DRAW);
  }
  glNamedBufferSubData(particleBuffer_, 0, GLsizeiptr(packed.size() * sizeof(float)), packed.data());
  glVertexArrayVertexBuffer(particleVao_, 0, particleBuffer_, 0, 16);
}

void Renderer::render(const Frame& f, const Camera& c, const RenderSettings& s) {
  if (!s.same_frame) uploadTerrain(f);
  const bool water = s.water && f.particles() > 0;
  const bool sameSurface = surfaceBuilt_ && builtWith_.cell_over_spacing == s.surface.cell_over_spacing &&
                           builtWith_.iso == s.surface.iso && builtWith_.occupancy == s.surface.occupancy;
  // The surface built last is of this very frame, or kept from an older one.
  const bool current = sameSurface && s.same_frame && !surfaceOld_;
  const bool built = current || (sameSurface && s.keep_surface);
  const bool kept = built && !current;
  if (water && !built) {
    surface_.setSettings(s.surface);
    surface_.update(f);
    surfaceBuilt_ = true, builtWith_ = s.surface;
    lightBuilt_ = false, surfaceOld_ = false;
  } else if (!s.same_frame) {
    surfaceOld_ = true;  // a new frame over the surface of an older one (kept, or the water off)
  }
  // The scene's extent, for the clip planes and the sun's view.
  const Eigen::Vector3f lo(float(f.x0), heightMin_, float(f.z0));
  const Eigen::Vector3f hi(float(f.x0 + f.dx * (f.nx - 1)), heightMax_ + 0.2f * (heightMax_ - heightMin_) + f.support,
                           float(f.z0 + f.dz * (f.nz - 1)));
  const Eigen::Vector3f centre = 0.5f * (lo + hi);
  const float radius = 0.5f * (hi - lo).norm() + 1e-3f;
  const float dist = (c.eye - centre).norm();
  const float near = std::max(1e-3f * radius, dist - radius), far = dist + radius;
  const Eigen::Matrix4f clipFromWorld = c.clipFromCamera(float(width_) / float(height_), near, far) * c.cameraFromWorld();
  const Eigen::Vector3f sun = s.sun.normalized();
  const bool caustics = water && s.caustics;
  if (caustics) {
    const Eigen::Vector3f up = std::abs(sun.y()) > 0.99f ? Eigen::Vector3f(0, 0, 1) : Eigen::Vector3f(0, 1, 0);
    lightClipFromWorld_ = ortho(-radius, radius, -radius, radius, 0.0f, 4 * radius) * lookAt(centre + 2 * radius * sun, centre, up);
    // The maps follow the surface (and the sun): a kept surface keeps them, though the terrain
    // under them may have moved by a frame's erosion.
    if (!lightBuilt_ || litBy_ != sun || litMap_ != s.caustic_map) {
      lightPass(f, s, lightClipFromWorld_);
      lightBuilt_ = true, litBy_ = sun, litMap_ = s.caustic_map;
    }
  }
  // Background: the terrain alone.
  glViewport(0, 0, width_, height_);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  const float skyColour[4] = {0.80f, 0.86f, 0.92f, 1.0f};
  const float one = 1.0f;
  glClearNamedFramebufferfv(backFbo_, GL_COLOR, 0, skyColour);
  glClearNamedFramebufferfv(backFbo_, GL_DEPTH, 0, &one);
  glBindFramebuffer(GL_FRAMEBUFFER, backFbo_);
  const GLuint tp = terrain_.id();
  glProgramUniform2f(tp, terrain_.location("origin"), float(f.x0), float(f.z0));
  glProgramUniform2f(tp, terrain_.location("spacing"), float(f.dx), float(f.dz));
  glProgramUniform1i(tp, terrain_.location("mode"), int(s.terrain));
  glProgramUniform1f(tp, terrain_.location("changeScale"), s.change_scale > 0 ? s.change_scale : std::max(changeMax_, 1e-9f));
  glProgramUniform2f(tp, terrain_.location("heightRange"), heightMin_, heightMax_);
  glProgramUniform3f(tp, terrain_.location("sunDir"), sun.x(), sun.y(), sun.z());
  glProgramUniform1i(tp, terrain_.location("caustics"), caustics ? 1 : 0);
  glProgramUniform1f(tp, terrain_.location("causticStrength"), s.caustic_strength);
  glProgramUniform1i(tp, terrain_.location("change"), 1);
  glProgramUniform1i(tp, terrain_.location("map"), 4);
  glProgramUniform1i(tp, terrain_.location("map2"), 5);
  glProgramUniform1f(tp, terrain_.location("mapScale"), std::max(mapMax_, 1e-30f));
  glProgramUniform1i(tp, terrain_.location("mapPair"), mapPair_ ? 1 : 0);
  glProgramUniform1i(tp, terrain_.location("causticMap"), 2);
  glProgramUniform1i(tp, terrain_.location("waterFromLight"), 3);
  setMatrix(terrain_, "lightClipFromWorld", lightClipFromWorld_);
  glBindTextureUnit(1, change_);
  glBindTextureUnit(4, map_), glBindTextureUnit(5, map2_);
  if (caustics) glBindTextureUnit(2, caustic_), glBindTextureUnit(3, waterPos_);
  drawTerrain(terrain_, clipFromWorld);
  // Final: the background, then the water over it, then the particles.
  glBlitNamedFramebuffer(backFbo_, finalFbo_, 0, 0, width_, height_, 0, 0, width_, height_,
                         GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, finalFbo_);
  if (water) {
    const GLuint wp = water_.id();
    setMatrix(water_, "clipFromWorld", clipFromWorld);
    glProgramUniform3f(wp, water_.location("eye"), c.eye.x(), c.eye.y(), c.eye.z());
    glProgramUniform3f(wp, water_.location("sunDir"), sun.x(), sun.y(), sun.z());
    glProgramUniform1i(wp, water_.location("reflections"), s.reflections ? 1 : 0);
    glProgramUniform1i(wp, water_.location("refraction"), s.refraction ? 1 : 0);
    glProgramUniform2f(wp, water_.location("viewport"), float(width_), float(height_));
    glProgramUniform2f(wp, water_.location("nearFar"), near, far);
    glProgramUniform1f(wp, water_.location("refractionStrength"), s.refraction_strength);
    glProgramUniform1i(wp, water_.location("sky"), 0);
    glProgramUniform1i(wp, water_.location("background"), 1);
    glProgramUniform1i(wp, water_.location("backgroundDepth"), 2);
    glBindTextureUnit(0, sky_);
    glBindTextureUnit(1, backColour_);
    glBindTextureUnit(2, backDepth_);
    water_.use();
    drawWater();
    if (s.spray && s.particles == RenderSettings::Particles::kOff)
      drawSpray(f, c, clipFromWorld, float(s.surface.iso), kept);
  }
  if (s.particles != RenderSettings::Particles::kOff && f.particles() > 0) {
    const bool bySpeed = s.particles == RenderSettings::Particles::kSpeed;
    float top = 1e-12f;
    uploadParticles(f, [&](size_t i) {
      const float v = bySpeed ? f.speed[i] : f.concentration[i];
      top = std::max(top, v);
      return v;
    });
    setMatrix(particles_, "clipFromWorld", clipFromWorld);
    glProgramUniform1f(particles_.id(), particles_.location("pointSize"), spritePixels(f, c, height_));
    glProgramUniform2f(particles_.id(), particles_.location("valueRange"), 0.0f, top);
    glEnable(GL_PROGRAM_POINT_SIZE);
    particles_.use();
    glBindVertexArray(particleVao_);
    glDrawArrays(GL_POINTS, 0, GLsizei(f.particles()));
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

// `keptSurface`: the surface is an older frame's, so this frame's particles are tested against
// its grid (those that moved out of it show); else the ones the surface was built from.
void Renderer::drawSpray(const Frame& f, const Camera& c, const Eigen::Matrix4f& clipFromWorld,
                         float iso, bool keptSurface) {
  const DensityGrid& g = surface_.grid();
  if (g.nodes.minCoeff() < 2) return;
  const GLuint sp = spray_.id();
  setMatrix(spray_, "clipFromWorld", clipFromWorld);
  glProgramUniform1f(sp, spray_.location("pointSize"), spritePixels(f, c, height_));
  glProgramUniform3f(sp, spray_.location("origin"), g.origin.x(), g.origin.y(), g.origin.z());
  glProgramUniform1f(sp, spray_.location("cell"), g.cell);
  glProgramUniform3i(sp, spray_.location("nodes"), g.nodes.x(), g.nodes.y(), g.nodes.z());
  glProgramUniform1f(sp, spray_.location("isoFixed"), float(iso * g.scale));
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the splat's atomics, read here
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, surface_.densityBuffer());
  if (keptSurface)
    uploadParticles(f, [](size_t) { return 1.0f; });
  else
    glVertexArrayVertexBuffer(particleVao_, 0, surface_.particleBuffer(), 0, 16);
  glEnable(GL_PROGRAM_POINT_SIZE);
  spray_.use();
  glBindVertexArray(particleVao_);
  glDrawArrays(GL_POINTS, 0, GLsizei(f.particles()));
}

std::vector<unsigned char> Renderer::readPixels() const {
  std::vector<unsigned char> rgba(size_t(width_) * height_ * 4);
  glGetTextureImage(finalColour_, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(rgba.size()), rgba.data());
  return topRowFirst(rgba, width_, height_);
}

void Renderer::writePng(const std::string& path) const {
  writeRgbaPng(path, width_, height_, readPixels());
}

void writeRgbaPng(const std::string& path, int width, int height,
                  const std::vector<unsigned char>& rgba) {
  std::vector<unsigned char> rgb(size_t(width) * size_t(height) * 3);
  for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
    for (int k = 0; k < 3; ++k) rgb[3 * i + size_t(k)] = rgba[4 * i + size_t(k)];
  std::string png;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_png_to_func(append, &png, width, height, 3, rgb.data(), width * 3))
    throw GlError(path + ": cannot encode the PNG");
  writeAtomically(path, [&](std::ostream& o) { o.write(png.data(), std::streamsize(png.size())); });
}

std::vector<unsigned char> readWindowPixels(int x, int y, int width, int height, int framebufferHeight) {
  std::vector<unsigned char> rgba(size_t(width) * size_t(height) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x, framebufferHeight - y - height, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  return topRowFirst(rgba, width, height);
}

void Renderer::blitTo(int width, int height) const {
  glBlitNamedFramebuffer(finalFbo_, 0, 0, 0, width_, height_, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

}  // namespace scour
