#include "study/measures.h"

namespace scour {

double suspendedSediment(const World& w) {
  double s = 0;
  for (double v : w.fluid().sed) s += v;
  return s;
}

Eigen::Vector3d sedimentCentroid(const World& w) {
  const Fluid& f = w.fluid();
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < f.size(); ++i) c += f.sed[i] * f.x[i].cast<double>();
  return c / suspendedSediment(w);
}

Eigen::Vector3d sedimentVariance(const World& w, const Eigen::Vector3d& about) {
  const Fluid& f = w.fluid();
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < f.size(); ++i)
    v += f.sed[i] * (f.x[i].cast<double>() - about).cwiseAbs2();
  return v / suspendedSediment(w);
}

double leastSquaresSlope(const std::vector<std::pair<double, double>>& samples) {
  double st = 0, sy = 0, stt = 0, sty = 0;
  const double n = double(samples.size());
  for (auto [t, y] : samples) st += t, sy += y, stt += t * t, sty += t * y;
  return (n * sty - st * sy) / (n * stt - st * st);
}

}  // namespace scour
