#pragma once
// Fluid particles as structure-of-arrays. Every per-particle array has size(); passes index them
// with the same i. Positions and velocities are float (bandwidth); quantities that must be
// conserved to rounding (sediment) are double. An array is added in one place, forEachArray:
// push, gather (reorders and removals), saving and loading a world state and the memory count
// all go through it.

#include <Eigen/Core>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace scour {

using Vec3f = Eigen::Vector3f;

/// Room for `need` elements; when the array must grow, an eighth more than that, not twice its size
/// (what push_back and resize do). The engine's arrays grow by a few elements a step (a source's
/// particles, the lists, the wetted tiles), and their slack is memory every particle pays for.
template <class Array>
inline void reserveWithSlack(Array& array, size_t need) {
  if (need > array.capacity()) array.reserve(need + need / 8 + 64);
}
/// Makes a per-particle array n long, growing it as reserveWithSlack does.
template <class Array>
inline void resizeForParticles(Array& array, size_t n) {
  reserveWithSlack(array, n);
  array.resize(n);
}

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

  /// Calls f(name, array) for every array that holds a particle's state (not `scratch`), in the
  /// order a world state stores them; `name` is what a corrupt state's message calls it.
  template <class F>
  void forEachArray(F&& f) {
    f("positions", x), f("velocities", v), f("accelerations", a), f("densities", rho);
    f("pressures", p), f("ids", id), f("sediment", sed);
  }
  template <class F>
  void forEachArray(F&& f) const {
    const_cast<Fluid&>(*this).forEachArray(
        [&](const char* name, const auto& array) { f(name, array); });
  }

  /// A new particle: every array gets a zero, then its place, velocity, id and density. A full
  /// array grows as reserveWithSlack does (the Z-order reorder trims it again).
  void push(const Vec3f& pos, const Vec3f& vel, uint32_t ident, float density) {
    forEachArray([](const char*, auto& array) {
      using T = typename std::remove_reference_t<decltype(array)>::value_type;
      reserveWithSlack(array, array.size() + 1);
      if constexpr (std::is_arithmetic_v<T>) array.push_back(T(0));
      else array.push_back(T::Zero());
    });
    x.back() = pos, v.back() = vel, id.back() = ident, rho.back() = density;
  }
  /// Bytes a particle takes in the arrays.
  static size_t bytesPerParticle() {
    size_t bytes = 0;
    Fluid probe;
    probe.forEachArray([&](const char*, const auto& array) {
      bytes += sizeof(typename std::remove_reference_t<decltype(array)>::value_type);
    });
    return bytes;
  }

  /// Applies a permutation: new[k] = old[order[k]]. Used by the Z-order reorder and by removals
  /// (order then lists the survivors, in their old order).
  void gather(const std::vector<uint32_t>& order);
};

}  // namespace scour
