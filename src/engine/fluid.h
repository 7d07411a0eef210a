#pragma once
// Fluid particles as structure-of-arrays. Every per-particle array has size(); passes index them
// with the same i. Positions and velocities are float (bandwidth); quantities that must be
// conserved to rounding (sediment, later) are double.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace scour {

using Vec3f = Eigen::Vector3f;

struct Fluid {
  std::vector<Vec3f> x;      ///< position [m]
  std::vector<Vec3f> v;      ///< velocity [m/s] (full step after a step completes)
  std::vector<Vec3f> a;      ///< acceleration at x [m/s²]
  std::vector<float> rho;    ///< density [kg/m³]
  std::vector<float> p;      ///< pressure [Pa]
  std::vector<uint32_t> id;  ///< creation number, stable across reorders
  std::vector<double> sed;   ///< suspended sediment volume [m³]; C = sed / V, V = m/ρ0
  std::vector<float> scratch;  ///< per-particle workspace of a pass (no meaning between passes)

  size_t size() const { return x.size(); }

  void push(const Vec3f& pos, const Vec3f& vel, uint32_t ident, float density) {
    x.push_back(pos);
    v.push_back(vel);
    a.push_back(Vec3f::Zero());
    rho.push_back(density);
    sed.push_back(0.0);
    p.push_back(0.0f);
    id.push_back(ident);
  }

  /// Applies a permutation: new[k] = old[order[k]]. Used by the Z-order reorder and by removals
  /// (order then lists the survivors, in their old order).
  void gather(const std::vector<uint32_t>& order);
};

}  // namespace scour
