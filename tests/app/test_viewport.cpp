// The window's view without a window: picking the terrain under a pixel and projecting a point
// back to its pixel are inverses; heights, distances and source placement by hand.
#include <catch2/catch.hpp>

#include "app/viewport.h"

using namespace scour;

namespace {

// A 1 m × 1 m terrain of 11 × 11 vertices rising along x: y = 0.2 + 0.1 x.
Frame slopeFrame() {
  Frame f;
  f.nx = f.nz = 11;
  f.dx = f.dz = 0.1;
  f.spacing = 0.02f;
  for (int k = 0; k < f.nz; ++k)
    for (int i = 0; i < f.nx; ++i) f.height.push_back(0.2f + 0.1f * float(i) * 0.1f);
  return f;
}

}  // namespace

TEST_CASE("terrain heights are bilinear on the grid and absent off it", "[app][viewport]") {
  const Frame f = slopeFrame();
  float g = 0;
  REQUIRE(terrainHeight(f, 0.0, 0.0, g));
  CHECK(g == Approx(0.2f));
  REQUIRE(terrainHeight(f, 0.55, 0.3, g));
  CHECK(g == Approx(0.255f));
  REQUIRE(terrainHeight(f, 1.0, 1.0, g));  // the far corner is on the grid
  CHECK(g == Approx(0.3f));
  CHECK_FALSE(terrainHeight(f, -0.01, 0.5, g));
  CHECK_FALSE(terrainHeight(f, 0.5, 1.01, g));
}

TEST_CASE("the terrain picked under a pixel projects back to that pixel", "[app][viewport]") {
  const Frame f = slopeFrame();
  const Orbit orbit = orbitFor(f);
  const Camera c = orbit.camera();
  // The orbit sees the terrain as the overview camera does.
  CHECK((c.eye - overviewCamera(f).eye).norm() < 1e-4f);
  const int w = 800, h = 600;
  const float aspect = float(w) / float(h);
  for (auto [mx, my] :
       {std::pair{400.0, 300.0}, std::pair{250.0, 380.0}, std::pair{520.0, 260.0}}) {
    INFO("pixel " << mx << ", " << my);
    Eigen::Vector3f hit;
    REQUIRE(pickTerrain(f, c, aspect, mx, my, w, h, hit));
    float g = 0;
    REQUIRE(terrainHeight(f, hit.x(), hit.z(), g));
    CHECK(hit.y() == Approx(g));
    Eigen::Vector2f pixel;
    REQUIRE(toWindow(c, aspect, hit, w, h, pixel));
    // The march steps half a cell (5 cm) along the ray, which spans up to about 20 pixels here:
    // the hit lies within a step past the surface (measured: 0.5 to 10 pixels off).
    CHECK(std::abs(pixel.x() - float(mx)) < 20.0f);
    CHECK(std::abs(pixel.y() - float(my)) < 20.0f);
  }
  // The sky above the terrain misses it; a point behind the camera has no pixel.
  Eigen::Vector3f hit;
  CHECK_FALSE(pickTerrain(f, c, aspect, 400.0, 0.0, w, h, hit));
  Eigen::Vector2f pixel;
  CHECK_FALSE(toWindow(c, aspect, c.eye + (c.eye - c.target), w, h, pixel));
}

TEST_CASE("distance to a segment, and a source kept over the terrain", "[app][viewport]") {
  CHECK(segmentDistance({0, 5}, {-10, 0}, {10, 0}) == Approx(5));
  CHECK(segmentDistance({13, 4}, {-10, 0}, {10, 0}) == Approx(5));  // past the end: to b
  CHECK(segmentDistance({3, 4}, {0, 0}, {0, 0}) == Approx(5));      // a point segment
  const Frame f = slopeFrame();
  // A disk of 0.1 m centred past the +x edge comes back to x = 0.9, 0.05 m above the terrain.
  const Eigen::Vector3d c = overTerrain(f, {1.2, 0.0, 0.5}, 0.1, 0.05);
  CHECK(c.x() == Approx(0.9));
  CHECK(c.z() == Approx(0.5));
  CHECK(c.y() == Approx(0.2 + 0.1 * 0.9 + 0.05).epsilon(1e-6));
}
