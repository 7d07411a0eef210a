#include "engine/heightfield.h"

#include <algorithm>
#include <cmath>

namespace scour {

Heightfield::Heightfield(int nx, int nz, double dx, double dz, double x0, double z0)
    : nx_(nx), nz_(nz), dx_(dx), dz_(dz), x0_(x0), z0_(z0), h_(size_t(nx) * nz, 0.0) {}

double Heightfield::minHeight() const { return *std::min_element(h_.begin(), h_.end()); }
double Heightfield::maxHeight() const { return *std::max_element(h_.begin(), h_.end()); }

SurfacePoint Heightfield::surface(double x, double z) const {
  double fx = std::clamp((x - x0_) / dx_, 0.0, double(nx_ - 1));
  double fz = std::clamp((z - z0_) / dz_, 0.0, double(nz_ - 1));
  int i = std::min(int(fx), nx_ - 2);
  int k = std::min(int(fz), nz_ - 2);
  double u = fx - i, w = fz - k;
  double h00 = at(i, k), h10 = at(i + 1, k), h01 = at(i, k + 1), h11 = at(i + 1, k + 1);
  double sx, sz, h;  // slopes dh/dx, dh/dz and height
  int t;
  if (u >= w) {
    sx = (h10 - h00) / dx_;
    sz = (h11 - h10) / dz_;
    h = h00 + u * (h10 - h00) + w * (h11 - h10);
    t = 0;
  } else {
    sx = (h11 - h01) / dx_;
    sz = (h01 - h00) / dz_;
    h = h00 + w * (h01 - h00) + u * (h11 - h01);
    t = 1;
  }
  Eigen::Vector3d n(-sx, 1.0, -sz);
  return {h, n.normalized(), 2 * (k * (nx_ - 1) + i) + t};
}

std::array<std::array<int, 2>, 3> Heightfield::triangleVertices(int tri) const {
  int cell = tri / 2, t = tri % 2;
  int i = cell % (nx_ - 1), k = cell / (nx_ - 1);
  if (t == 0) return {{{i, k}, {i + 1, k}, {i + 1, k + 1}}};
  return {{{i, k}, {i + 1, k + 1}, {i, k + 1}}};
}

std::array<Eigen::Vector3d, 3> Heightfield::triangleCorners(int tri) const {
  auto v = triangleVertices(tri);
  std::array<Eigen::Vector3d, 3> c;
  for (int a = 0; a < 3; ++a)
    c[a] = {x0_ + dx_ * v[a][0], at(v[a][0], v[a][1]), z0_ + dz_ * v[a][1]};
  return c;
}

}  // namespace scour
