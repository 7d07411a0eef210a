// Pictures of a small pool, headless on llvmpipe: no GL error; water-coloured pixels where the
// water is and none on the dry side; every water effect changes the picture when toggled; EGL
// and OSMesa draw the same picture; spray shows the water the surface does not cover; a kept
// surface (the window between two rebuilds) is drawn as built, the new frame's particles that
// left it as spray.
#include <catch2/catch.hpp>

#include "render/context.h"
#include "render/renderer.h"
#include "scene/presets.h"

using namespace scour;

namespace {

constexpr int kW = 160, kH = 120;

// A flat 1 × 1 m floor; a pool over x ∈ [0.05, 0.4] with a mound of water on it (a curved
// surface, so the caustics have something to focus).
Frame pool() {
  SceneSpec s;
  s.params.spacing = 0.02;
  s.terrain = flatTerrain(1.0, 1.0, 0.05);
  WaterBlock b;
  b.min = {0.05, 0.0, 0.1};
  b.max = {0.4, 0.06, 0.9};
  s.blocks.push_back(b);
  Scene scene = buildScene(s);
  for (int k = -4; k <= 4; ++k)
    for (int j = 0; j <= 4; ++j)
      for (int i = -4; i <= 4; ++i)
        if (i * i + j * j + k * k <= 16)
          scene.desc.particles.push_back(Eigen::Vector3f(0.22f + 0.02f * i, 0.07f + 0.02f * j, 0.5f + 0.02f * k)),
              scene.desc.pressure.push_back(0.0f);
  World w(scene.desc);
  return makeFrame(w);
}

Camera topDown() {
  Camera c;
  c.eye = {0.5f, 1.6f, 0.5f};
  c.target = {0.5f, 0.0f, 0.5f};
  c.up = {0.0f, 0.0f, -1.0f};
  return c;
}

// The pixel column of world x on the floor (y = 0) seen from topDown().
int column(float x) {
  const float half = 1.6f * std::tan(20.0f * float(M_PI) / 180.0f) * kW / kH;
  return int((x - 0.5f) / half * 0.5f * kW + 0.5f * kW);
}

// Water-coloured: bluer than the same pixel of the picture without water (the water tints and
// darkens the floor it covers towards its deep blue-green).
bool watery(const std::vector<unsigned char>& img, const std::vector<unsigned char>& bare, int x, int y) {
  const unsigned char* p = &img[size_t(4 * (y * kW + x))];
  const unsigned char* q = &bare[size_t(4 * (y * kW + x))];
  return (int(p[2]) - int(p[0])) - (int(q[2]) - int(q[0])) > 20;
}

std::vector<unsigned char> picture(GlContext& gl, const Frame& f, const RenderSettings& s) {
  Renderer r(kW, kH);
  r.render(f, topDown(), s);
  while (r.surface().growIfOverflowed()) r.render(f, topDown(), s);
  auto img = r.readPixels();
  CHECK(gl.errors() == 0);
  return img;
}

long differing(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b, int tolerance) {
  long n = 0;
  for (size_t i = 0; i < a.size(); i += 4)
    for (int k = 0; k < 3; ++k)
      if (std::abs(int(a[i + size_t(k)]) - int(b[i + size_t(k)])) > tolerance) {
        ++n;
        break;
      }
  return n;
}

}  // namespace

TEST_CASE("a picture of a pool: water where the water is, none on the dry side", "[render][picture]") {
  auto gl = createGlContext(GlBackend::kEgl);
  const Frame f = pool();
  RenderSettings s;
  s.terrain = RenderSettings::Terrain::kShaded;
  const auto img = picture(*gl, f, s);
  s.water = false;
  const auto bare = picture(*gl, f, s);
  long wet = 0, wetTotal = 0, dry = 0, dryChanged = 0;
  for (int y = kH / 4; y < 3 * kH / 4; ++y) {
    for (int x = column(0.12f); x <= column(0.33f); ++x) wet += watery(img, bare, x, y), ++wetTotal;
    for (int x = column(0.6f); x <= column(0.95f); ++x) {
      dry += watery(img, bare, x, y);
      for (int k = 0; k < 3; ++k) dryChanged += img[size_t(4 * (y * kW + x) + k)] != bare[size_t(4 * (y * kW + x) + k)];
    }
  }
  CHECK(wetTotal > 200);
  CHECK(wet > 0.95 * double(wetTotal));
  CHECK(dry == 0);
  CHECK(dryChanged == 0);  // the dry floor is drawn exactly as without water
}

TEST_CASE("each water effect changes the picture when toggled", "[render][picture]") {
  auto gl = createGlContext(GlBackend::kEgl);
  const Frame f = pool();
  RenderSettings all;
  all.terrain = RenderSettings::Terrain::kShaded;
  const auto full = picture(*gl, f, all);
  for (bool RenderSettings::*effect : {&RenderSettings::reflections, &RenderSettings::refraction,
                                       &RenderSettings::caustics}) {
    RenderSettings s = all;
    s.*effect = false;
    const long changed = differing(full, picture(*gl, f, s), 2);
    INFO("pixels changed: " << changed);
    CHECK(changed > 20);
  }
  // The same settings twice: the same picture.
  CHECK(differing(full, picture(*gl, f, all), 0) == 0);
}

TEST_CASE("EGL and OSMesa draw the same picture", "[render][picture]") {
  const Frame f = pool();
  RenderSettings s;
  std::vector<unsigned char> img[2];
  int k = 0;
  for (GlBackend b : {GlBackend::kEgl, GlBackend::kOsMesa}) {
    auto gl = createGlContext(b);
    img[k++] = picture(*gl, f, s);
  }
  const long off = differing(img[0], img[1], 2);
  INFO("pixels differing by more than 2 levels: " << off);
  CHECK(off <= kW * kH / 200);  // at most 0.5 %
}

TEST_CASE("spray: water the surface does not cover is drawn as sprites", "[render][picture]") {
  auto gl = createGlContext(GlBackend::kEgl);
  Frame f = pool();
  // Drops in flight over the dry side, 10 cm apart: each alone, its density a fifth of the iso
  // level, so no surface is drawn around it.
  for (float x : {0.65f, 0.75f, 0.85f})
    for (float z : {0.3f, 0.5f, 0.7f}) {
      f.position.emplace_back(x, 0.3f, z);
      f.concentration.push_back(0.0f);
      f.speed.push_back(1.0f);
    }
  RenderSettings s;
  s.terrain = RenderSettings::Terrain::kShaded;
  const auto with = picture(*gl, f, s);
  s.spray = false;
  const auto without = picture(*gl, f, s);
  // Over the dry side only the drops differ, and each drop shows.
  long changed = 0;
  int drops = 0;
  for (float x : {0.65f, 0.75f, 0.85f}) {
    bool seen = false;
    for (int y = 0; y < kH; ++y)
      for (int dx = -3; dx <= 3; ++dx) {
        // 0.3 m up, nearer the camera: where the floor's 0.5 + (x − 0.5)·1.6/1.3 would be.
        const int c = std::clamp(column(0.5f + (x - 0.5f) * 1.6f / 1.3f) + dx, 0, kW - 1);
        const unsigned char* p = &with[size_t(4 * (y * kW + c))];
        const unsigned char* q = &without[size_t(4 * (y * kW + c))];
        seen |= p[0] != q[0] || p[1] != q[1] || p[2] != q[2];
      }
    drops += seen;
  }
  for (int y = 0; y < kH; ++y)
    for (int x = column(0.6f); x < kW; ++x) {
      const unsigned char* p = &with[size_t(4 * (y * kW + x))];
      const unsigned char* q = &without[size_t(4 * (y * kW + x))];
      changed += p[0] != q[0] || p[1] != q[1] || p[2] != q[2];
    }
  CHECK(drops == 3);
  CHECK(changed > 9);
  // Without the drops the dry side is the same with spray on or off: nothing is made up.
  const Frame plain = pool();
  s.spray = true;
  const auto a = picture(*gl, plain, s);
  s.spray = false;
  const auto b = picture(*gl, plain, s);
  long dryDiff = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = column(0.6f); x < kW; ++x)
      for (int k = 0; k < 3; ++k) dryDiff += a[size_t(4 * (y * kW + x) + k)] != b[size_t(4 * (y * kW + x) + k)];
  CHECK(dryDiff == 0);
}

TEST_CASE("a kept surface: the old triangles drawn, the new frame's particles outside them as spray",
          "[render][picture]") {
  auto gl = createGlContext(GlBackend::kEgl);
  const Frame before = pool();
  // The next frame: all the water moved half a metre along x, onto the side that was dry.
  Frame after = before;
  for (auto& p : after.position) p.x() += 0.5f;
  RenderSettings s;
  s.terrain = RenderSettings::Terrain::kShaded;
  // A renderer that built the surface of `before`, then draws `after` keeping it.
  auto kept = [&](bool spray, Eigen::Vector3f* origin) {
    Renderer r(kW, kH);
    r.render(before, topDown(), s);
    while (r.surface().growIfOverflowed()) r.render(before, topDown(), s);
    const Eigen::Vector3f built = r.surface().grid().origin;
    RenderSettings k = s;
    k.keep_surface = true;
    k.spray = spray;
    r.render(after, topDown(), k);
    CHECK(r.surface().grid().origin == built);  // not built again
    if (origin) *origin = built;
    auto img = r.readPixels();
    CHECK(gl->errors() == 0);
    return img;
  };
  Eigen::Vector3f keptOrigin;
  const auto withSpray = kept(true, &keptOrigin);
  const auto noSpray = kept(false, nullptr);
  RenderSettings dry = s;
  dry.water = false;
  const auto bare = picture(*gl, after, dry);
  const auto fresh = picture(*gl, after, s);
  long oldWet = 0, freshWet = 0, total = 0;
  for (int y = kH / 4; y < 3 * kH / 4; ++y)
    for (int x = column(0.12f); x <= column(0.33f); ++x)
      oldWet += watery(withSpray, bare, x, y), freshWet += watery(fresh, bare, x, y), ++total;
  INFO("old pool pixels: " << total << ", water kept on " << oldWet << ", on a rebuilt surface " << freshWet);
  CHECK(total > 200);
  CHECK(oldWet > 0.95 * double(total));  // the old triangles, where the water was
  CHECK(freshWet == 0);                  // a rebuilt surface has left it
  // Where the water went, the kept surface has no triangles: the particles show as sprites, and
  // without spray that side is drawn as if dry.
  long sprites = 0, noSprayOff = 0, cells = 0;
  for (int y = kH / 4; y < 3 * kH / 4; ++y)
    for (int x = column(0.62f); x <= column(0.83f); ++x) {
      const size_t i = size_t(4 * (y * kW + x));
      bool a = false, b = false;
      for (int k = 0; k < 3; ++k) a |= withSpray[i + size_t(k)] != bare[i + size_t(k)], b |= noSpray[i + size_t(k)] != bare[i + size_t(k)];
      sprites += a, noSprayOff += b, ++cells;
    }
  INFO("new water pixels: " << cells << ", drawn as sprites " << sprites << ", changed without spray " << noSprayOff);
  CHECK(sprites > 0.5 * double(cells));
  CHECK(noSprayOff == 0);
}
