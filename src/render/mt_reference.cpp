#include "render/mt_reference.h"

namespace scour {

namespace {

constexpr int kTetra[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7},
                              {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};

struct Marcher {
  const DensityGrid& g;
  float iso;
  std::vector<SurfaceTriangle>& out;
  Eigen::Vector3i corner[8];
  float val[8];

  long index(const Eigen::Vector3i& n) const {
    return (long(n.z()) * g.nodes.y() + n.y()) * g.nodes.x() + n.x();
  }
  float value(const Eigen::Vector3i& n) const { return float(g.value[size_t(index(n))]); }
  Eigen::Vector3f gradient(const Eigen::Vector3i& n) const {
    const Eigen::Vector3i lo = (n.array() - 1).max(0), hi = (n + Eigen::Vector3i::Ones()).cwiseMin(g.nodes - Eigen::Vector3i::Ones());
    return {value({hi.x(), n.y(), n.z()}) - value({lo.x(), n.y(), n.z()}),
            value({n.x(), hi.y(), n.z()}) - value({n.x(), lo.y(), n.z()}),
            value({n.x(), n.y(), hi.z()}) - value({n.x(), n.y(), lo.z()})};
  }
  Eigen::Vector3f node(const Eigen::Vector3i& n) const { return g.origin + g.cell * n.cast<float>(); }
  SurfaceVertex edge(int a, int b) const {
    if (index(corner[b]) < index(corner[a])) std::swap(a, b);
    const float t = (iso - val[a]) / (val[b] - val[a]);
    const Eigen::Vector3f pa = node(corner[a]), pb = node(corner[b]);
    SurfaceVertex v;
    v.position = pa + t * (pb - pa);
    const Eigen::Vector3f ga = gradient(corner[a]), gb = gradient(corner[b]);
    v.normal = (-(ga + t * (gb - ga))).normalized();
    return v;
  }
  void emit(SurfaceVertex a, SurfaceVertex b, SurfaceVertex c, const Eigen::Vector3f& inside) {
    if ((b.position - a.position).cross(c.position - a.position).dot(inside - a.position) > 0) std::swap(b, c);
    out.push_back({a, b, c});
  }
  void cell(const Eigen::Vector3i& c) {
    int inside = 0;
    for (int k = 0; k < 8; ++k) {
      corner[k] = c + Eigen::Vector3i(k & 1, (k >> 1) & 1, (k >> 2) & 1);
      val[k] = value(corner[k]);
      inside += val[k] > iso;
    }
    if (inside == 0 || inside == 8) return;
    for (const auto& t : kTetra) {
      int in[4], outv[4], ni = 0, no = 0;
      for (int v : t) (val[v] > iso ? in[ni++] : outv[no++]) = v;
      if (ni == 0 || ni == 4) continue;
      Eigen::Vector3f centre = Eigen::Vector3f::Zero();
      for (int k = 0; k < ni; ++k) centre += node(corner[in[k]]);
      centre /= float(ni);
      if (ni == 1) {
        emit(edge(in[0], outv[0]), edge(in[0], outv[1]), edge(in[0], outv[2]), centre);
      } else if (ni == 3) {
        emit(edge(outv[0], in[0]), edge(outv[0], in[1]), edge(outv[0], in[2]), centre);
      } else {
        const SurfaceVertex p0 = edge(in[0], outv[0]), p1 = edge(in[0], outv[1]);
        const SurfaceVertex p2 = edge(in[1], outv[1]), p3 = edge(in[1], outv[0]);
        emit(p0, p1, p2, centre);
        emit(p0, p2, p3, centre);
      }
    }
  }
};

}  // namespace

std::vector<SurfaceTriangle> marchTetrahedraCpu(const DensityGrid& grid, double iso) {
  std::vector<SurfaceTriangle> out;
  Marcher m{grid, float(iso * grid.scale), out, {}, {}};
  for (int z = 0; z + 1 < grid.nodes.z(); ++z)
    for (int y = 0; y + 1 < grid.nodes.y(); ++y)
      for (int x = 0; x + 1 < grid.nodes.x(); ++x) m.cell({x, y, z});
  return out;
}

}  // namespace scour
