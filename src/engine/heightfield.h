#pragma once
// The terrain: a regular grid of heights over the x–z plane (y is up), two triangles per cell.
// Cell (i, k) spans vertices i..i+1 along x and k..k+1 along z; it is split along the diagonal
// from vertex (i, k) to (i+1, k+1). Triangle t of cell (i, k) has id 2·(k·(nx−1) + i) + t, with
// t = 0 the triangle (i,k), (i+1,k), (i+1,k+1) and t = 1 the triangle (i,k), (i+1,k+1), (i,k+1).
// Heights are double: the soil budget is kept to rounding.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace scour {

/// Distance from p to the nearest point of the triangle (a, b, c) (Ericson's closest-point
/// regions) [m].
double pointTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b, const Eigen::Vector3d& c);

struct SurfacePoint {
  double height;
  Eigen::Vector3d normal;  ///< unit, pointing up out of the terrain
  int triangle;
};

class Heightfield {
 public:
  Heightfield() = default;
  /// nx × nz vertices, spacing dx along x and dz along z, vertex (0,0) at (x0, z0).
  Heightfield(int nx, int nz, double dx, double dz, double x0 = 0.0, double z0 = 0.0);

  int nx() const { return nx_; }
  int nz() const { return nz_; }
  double dx() const { return dx_; }
  double dz() const { return dz_; }
  double x0() const { return x0_; }
  double z0() const { return z0_; }
  double xMax() const { return x0_ + dx_ * (nx_ - 1); }
  double zMax() const { return z0_ + dz_ * (nz_ - 1); }
  int triangleCount() const { return 2 * (nx_ - 1) * (nz_ - 1); }

  double& at(int i, int k) { return h_[size_t(k) * nx_ + i]; }
  double at(int i, int k) const { return h_[size_t(k) * nx_ + i]; }
  const std::vector<double>& heights() const { return h_; }
  std::vector<double>& heights() { return h_; }
  double minHeight() const;
  double maxHeight() const;

  /// Height, unit normal and triangle of the surface above (x, z); points outside the grid are
  /// clamped to its edge.
  /// (Inline, as heightAt: they run several times per particle and step, and heightAt needs no
  /// normal.)
  SurfacePoint surface(double x, double z) const {
    const Cell c = cellAt(x, z);
    const bool lower = c.u >= c.w;  // triangle 0 of the cell (else 1)
    // Slopes dh/dx and dh/dz of the triangle.
    const double sx = lower ? (c.h10 - c.h00) / dx_ : (c.h11 - c.h01) / dx_;
    const double sz = lower ? (c.h11 - c.h10) / dz_ : (c.h01 - c.h00) / dz_;
    const Eigen::Vector3d n(-sx, 1.0, -sz);
    return {heightIn(c), n.normalized(), 2 * (c.k * (nx_ - 1) + c.i) + (lower ? 0 : 1)};
  }
  /// surface(x, z).height, to the bit.
  double heightAt(double x, double z) const { return heightIn(cellAt(x, z)); }

  /// Distance from p to the nearest point of a triangle [m].
  double distanceToTriangle(int tri, const Eigen::Vector3d& p) const {
    const auto [a, b, c] = triangleCorners(tri);
    return pointTriangleDistance(p, a, b, c);
  }
  /// Distance from p to the surface: the nearest of the triangles of the 3 × 3 cells around p's
  /// cell (enough for a point within a cell of the surface) [m].
  double distanceToSurface(const Eigen::Vector3d& p) const;
  /// The three corners (x, h, z) of a triangle.
  std::array<Eigen::Vector3d, 3> triangleCorners(int tri) const;
  /// Vertex indices (i, k) of a triangle's corners, in the order of triangleCorners.
  std::array<std::array<int, 2>, 3> triangleVertices(int tri) const;
  /// The same corners as indices k·nx + i into heights().
  std::array<size_t, 3> triangleVertexIndices(int tri) const {
    const int cell = tri / 2;
    const size_t v = size_t(cell / (nx_ - 1)) * size_t(nx_) + size_t(cell % (nx_ - 1)), up = size_t(nx_);
    if (tri % 2 == 0) return {v, v + 1, v + up + 1};
    return {v, v + up + 1, v + up};
  }

 private:
  /// The cell under (x, z), the place in it and its corners' heights.
  struct Cell {
    int i, k;
    double u, w, h00, h10, h01, h11;
  };
  Cell cellAt(double x, double z) const {
    // A place that is not a number reads the corner cell (clamp would pass NaN through, and the
    // cell index of NaN reads memory outside the grid): the invariant check then names the particle.
    auto cellCoordinate = [](double q, int last) { return q > 0.0 ? std::min(q, double(last)) : 0.0; };
    const double fx = cellCoordinate((x - x0_) / dx_, nx_ - 1);
    const double fz = cellCoordinate((z - z0_) / dz_, nz_ - 1);
    const int i = std::min(int(fx), nx_ - 2);
    const int k = std::min(int(fz), nz_ - 2);
    return {i, k, fx - i, fz - k, at(i, k), at(i + 1, k), at(i, k + 1), at(i + 1, k + 1)};
  }
  /// The height at the cell's place, on its triangle.
  static double heightIn(const Cell& c) {
    return c.u >= c.w ? c.h00 + c.u * (c.h10 - c.h00) + c.w * (c.h11 - c.h10)
                      : c.h00 + c.w * (c.h01 - c.h00) + c.u * (c.h11 - c.h01);
  }

  int nx_ = 0, nz_ = 0;
  double dx_ = 1, dz_ = 1, x0_ = 0, z0_ = 0;
  std::vector<double> h_;
};

/// The surface the walls see (docs/model.md, "the wall surface"): the terrain's highest point
/// within a radius (Δs/2) of each vertex, averaged over the same disk. It is never below the
/// terrain (every vertex within the radius of a vertex has that vertex in its own disk), and it
/// has no feature narrower than the radius: fluid particles cannot resolve one, and a plane that
/// turns with every cell of a terrain rougher than Δs pumped energy into the particles over it.
/// A grid coarser than the radius has no vertex but the centre in any disk: the surface is the
/// terrain itself, and nothing is copied.
class WallSurface {
 public:
  WallSurface() = default;
  WallSurface(const Heightfield& terrain, double radius);
  /// Follows the terrain after the heights of `movedVertices` (k·nx + i, each once) changed
  /// (applyTerrainChange).
  void follow(const Heightfield& terrain, const std::vector<int>& movedVertices);
  const Heightfield& of(const Heightfield& terrain) const {
    return disk_.empty() ? terrain : smooth_;
  }
  bool filters() const { return !disk_.empty(); }

 private:
  std::vector<std::array<int, 2>> disk_;  // vertex offsets within the radius
  Heightfield highest_, smooth_;
  std::vector<uint32_t> mark_;
  uint32_t epoch_ = 0;
  double filtered(const Heightfield& in, int i, int k, bool highest) const;
  std::vector<int> spread(const Heightfield& t, const std::vector<int>& vertices);
};

}  // namespace scour
