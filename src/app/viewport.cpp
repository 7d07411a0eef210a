#include "app/viewport.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <vector>

namespace scour {

namespace {
// Any clip planes do: a pixel's ray and a point's pixel do not depend on them. The far one also
// ends the march.
constexpr float kNear = 0.01f, kFar = 1000.0f;
}  // namespace

Camera Orbit::camera() const {
  Camera c;
  c.target = target;
  c.eye = target + distance * Eigen::Vector3f(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                              std::cos(pitch) * std::cos(yaw));
  return c;
}

Orbit orbitFor(const Frame& f) {
  const Camera c = overviewCamera(f);
  Orbit o;
  o.target = c.target;
  const Eigen::Vector3f d = c.eye - c.target;
  o.distance = d.norm();
  o.pitch = std::asin(d.y() / o.distance);
  o.yaw = std::atan2(d.x(), d.z());
  return o;
}

Orbit fitOrbit(const Frame& f, Orbit o, float aspect, int w, int h, float x, float y, float rw,
               float rh) {
  if (f.nx < 2 || f.nz < 2 || rw < 16 || rh < 16) return o;
  // The terrain as a 9 × 9 lattice of its points: its outline in the picture, near enough.
  std::vector<Eigen::Vector3f> points;
  for (int a = 0; a <= 8; ++a)
    for (int b = 0; b <= 8; ++b) {
      const int i = (f.nx - 1) * a / 8, k = (f.nz - 1) * b / 8;
      points.emplace_back(float(f.x0 + i * f.dx), f.height[size_t(k) * size_t(f.nx) + size_t(i)],
                          float(f.z0 + k * f.dz));
    }
  for (int iteration = 0; iteration < 40; ++iteration) {
    const Camera c = o.camera();
    Eigen::Vector2f lo(1e30f, 1e30f), hi(-1e30f, -1e30f), p;
    for (const Eigen::Vector3f& q : points) {
      if (!toWindow(c, aspect, q, w, h, p)) return o;  // behind the camera: leave it
      lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    }
    // Pan the picture's centre onto the rectangle's, then zoom to fill 90 % of it.
    const Eigen::Vector2f offset = Eigen::Vector2f(x + 0.5f * rw, y + 0.5f * rh) - 0.5f * (lo + hi);
    const float fill = std::max((hi.x() - lo.x()) / rw, (hi.y() - lo.y()) / rh) / 0.9f;
    const Eigen::Vector3f forward = (c.target - c.eye).normalized();
    const Eigen::Vector3f right = forward.cross(Eigen::Vector3f::UnitY()).normalized();
    const Eigen::Vector3f up = right.cross(forward);
    const float perPixel =
        2 * o.distance * std::tan(0.5f * c.fov_deg * float(M_PI) / 180) / float(h);
    o.target -= perPixel * (offset.x() * right - offset.y() * up);
    o.distance *= std::clamp(fill, 0.5f, 2.0f);
    if (offset.norm() < 0.5f && std::abs(fill - 1) < 1e-3f) break;
  }
  return o;
}

bool terrainHeight(const Frame& f, double x, double z, float& height) {
  const double u = (x - f.x0) / f.dx, v = (z - f.z0) / f.dz;
  if (!(u >= 0 && v >= 0 && u <= f.nx - 1 && v <= f.nz - 1) || f.nx < 2 || f.nz < 2) return false;
  const int i = std::min(int(u), f.nx - 2), k = std::min(int(v), f.nz - 2);
  const float fu = float(u - i), fv = float(v - k);
  auto at = [&](int di, int dk) {
    return f.height[size_t(k + dk) * size_t(f.nx) + size_t(i + di)];
  };
  height =
      (1 - fv) * ((1 - fu) * at(0, 0) + fu * at(1, 0)) + fv * ((1 - fu) * at(0, 1) + fu * at(1, 1));
  return true;
}

bool pickTerrain(const Frame& f, const Camera& c, float aspect, double mx, double my, int w, int h,
                 Eigen::Vector3f& hit) {
  const Eigen::Matrix4f worldFromClip =
      (c.clipFromCamera(aspect, kNear, kFar) * c.cameraFromWorld()).inverse();
  const float x = float(2 * mx / w - 1), y = float(1 - 2 * my / h);
  const Eigen::Vector4f a = worldFromClip * Eigen::Vector4f(x, y, -1, 1);
  const Eigen::Vector4f b = worldFromClip * Eigen::Vector4f(x, y, 1, 1);
  const Eigen::Vector3f p0 = a.head<3>() / a.w(), p1 = b.head<3>() / b.w();
  const Eigen::Vector3f dir = (p1 - p0).normalized();
  const float step = float(std::min(f.dx, f.dz)) * 0.5f;
  Eigen::Vector3f p = p0;
  for (int s = 0; s < 200000; ++s, p += step * dir) {
    float height = 0;
    if (terrainHeight(f, p.x(), p.z(), height) && p.y() <= height) {
      hit = {p.x(), height, p.z()};
      return true;
    }
    if ((p - p0).norm() > kFar) break;
  }
  return false;
}

bool toWindow(const Camera& c, float aspect, const Eigen::Vector3f& p, int w, int h,
              Eigen::Vector2f& pixel) {
  const Eigen::Matrix4f clipFromWorld = c.clipFromCamera(aspect, kNear, kFar) * c.cameraFromWorld();
  const Eigen::Vector4f q = clipFromWorld * Eigen::Vector4f(p.x(), p.y(), p.z(), 1);
  if (!(q.w() > 1e-6f)) return false;
  pixel = {float((q.x() / q.w() + 1) * 0.5 * w), float((1 - q.y() / q.w()) * 0.5 * h)};
  return std::isfinite(pixel.x()) && std::isfinite(pixel.y());
}

float segmentDistance(const Eigen::Vector2f& p, const Eigen::Vector2f& a,
                      const Eigen::Vector2f& b) {
  const Eigen::Vector2f u = b - a;
  const float len2 = u.squaredNorm();
  const float t = len2 > 0 ? std::clamp((p - a).dot(u) / len2, 0.0f, 1.0f) : 0.0f;
  return (p - a - t * u).norm();
}

Eigen::Vector3d overTerrain(const Frame& f, Eigen::Vector3d centre, double radius, double lift) {
  const double x1 = f.x0 + (f.nx - 1) * f.dx, z1 = f.z0 + (f.nz - 1) * f.dz;
  if (x1 - f.x0 > 2 * radius) centre.x() = std::clamp(centre.x(), f.x0 + radius, x1 - radius);
  if (z1 - f.z0 > 2 * radius) centre.z() = std::clamp(centre.z(), f.z0 + radius, z1 - radius);
  float g = float(centre.y());
  terrainHeight(f, centre.x(), centre.z(), g);
  centre.y() = g + lift;
  return centre;
}

}  // namespace scour
