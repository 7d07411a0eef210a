#include "engine/sources.h"

#include <cmath>

namespace scour {

std::vector<Eigen::Vector2d> diskLattice(double radius, double spacing) {
  std::vector<Eigen::Vector2d> points;
  const int r = int(std::ceil(radius / spacing));
  for (int b = -r; b <= r; ++b)
    for (int a = -r; a <= r; ++a) {
      const double u = a * spacing, w = b * spacing;
      if (u * u + w * w <= radius * radius + 1e-12) points.emplace_back(u, w);
    }
  if (points.empty()) points.emplace_back(0.0, 0.0);
  return points;
}

Emitter::Emitter(const Source& s, double spacing) : src(s) {
  src.direction.normalize();
  // An orthonormal basis (e1, e2) of the disk plane.
  Eigen::Vector3d helper = std::abs(src.direction.y()) < 0.9 ? Eigen::Vector3d::UnitY()
                                                              : Eigen::Vector3d::UnitX();
  Eigen::Vector3d e1 = src.direction.cross(helper).normalized();
  Eigen::Vector3d e2 = src.direction.cross(e1);
  for (const Eigen::Vector2d& uw : diskLattice(src.radius, spacing))
    slots.push_back(uw.x() * e1 + uw.y() * e2);
  speed = src.rate / (double(slots.size()) * spacing * spacing);
  travelled = spacing;  // the first layer is due at the start time
}

namespace {
uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}
}  // namespace

std::pair<double, double> RainState::point(uint64_t seed, uint64_t k) {
  const uint64_t a = splitmix64(seed * 0x632BE59BD9B4E019ULL + 2 * k);
  const uint64_t b = splitmix64(seed * 0x632BE59BD9B4E019ULL + 2 * k + 1);
  return {double(a >> 11) * 0x1.0p-53, double(b >> 11) * 0x1.0p-53};
}

}  // namespace scour
