#pragma once
// The window's view of the scene, as pure math over a Frame and a camera: the orbit camera,
// the terrain under the mouse, and where a world point lands in the window. No GL, no ImGui
// (tests/app/test_viewport.cpp). Window pixels run x right, y down, from the top-left corner.

#include <Eigen/Core>

#include "engine/frame.h"
#include "render/renderer.h"

namespace scour {

/// Orbit camera: yaw and pitch around a target, at a distance.
struct Orbit {
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  float yaw = -0.6f, pitch = 0.7f, distance = 3.0f;
  Camera camera() const;
};

/// The orbit that looks as overviewCamera(f) does.
Orbit orbitFor(const Frame& f);

/// The orbit panned and zoomed (same yaw and pitch) so the terrain fills the window rectangle at
/// (x, y) of size rw × rh in a w × h window, as far as it can: the part of the window the
/// panels leave free.
Orbit fitOrbit(const Frame& f, Orbit o, float aspect, int w, int h, float x, float y, float rw,
               float rh);

/// The frame's terrain height at (x, z), bilinear between vertices; false off the grid.
bool terrainHeight(const Frame& f, double x, double z, float& height);

/// The point of the terrain under the window pixel (mx, my) of a w × h window: a march along
/// the ray through the pixel in steps of half a cell. False if the ray misses the terrain.
bool pickTerrain(const Frame& f, const Camera& c, float aspect, double mx, double my, int w, int h,
                 Eigen::Vector3f& hit);

/// The window pixel a world point projects to (pickTerrain's inverse). False behind the camera.
bool toWindow(const Camera& c, float aspect, const Eigen::Vector3f& p, int w, int h,
              Eigen::Vector2f& pixel);

/// Pixels from p to the segment ab.
float segmentDistance(const Eigen::Vector2f& p, const Eigen::Vector2f& a, const Eigen::Vector2f& b);

/// A source's centre moved so its disk lies over the terrain (a disk reaching past a closed wall
/// would emit particles outside it), at `lift` above the terrain there. Unchanged along an axis
/// where the terrain is narrower than the disk.
Eigen::Vector3d overTerrain(const Frame& f, Eigen::Vector3d centre, double radius, double lift);

}  // namespace scour
