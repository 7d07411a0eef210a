#include "engine/sources.h"

#include <cmath>

namespace scour {

Emitter::Emitter(const Source& s, double spacing) : src(s) {
  src.direction.normalize();
  // An orthonormal basis (e1, e2) of the disk plane.
  Eigen::Vector3d helper = std::abs(src.direction.y()) < 0.9 ? Eigen::Vector3d::UnitY()
                                                              : Eigen::Vector3d::UnitX();
  Eigen::Vector3d e1 = src.direction.cross(helper).normalized();
  Eigen::Vector3d e2 = src.direction.cross(e1);
  int r = int(std::ceil(src.radius / spacing));
  for (int b = -r; b <= r; ++b)
    for (int a = -r; a <= r; ++a) {
      double u = a * spacing, w = b * spacing;
      if (u * u + w * w <= src.radius * src.radius + 1e-12) slots.push_back(u * e1 + w * e2);
    }
  if (slots.empty()) slots.push_back(Eigen::Vector3d::Zero());
  speed = src.rate / (double(slots.size()) * spacing * spacing);
  travelled = spacing;  // the first layer is due at the start time
}

}  // namespace scour
