#pragma once
// Measures of a run shared by the study and the tests: the suspended sediment, its centre and
// spread, and the least-squares slope of a time series.

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "engine/world.h"

namespace scour {

/// Total sediment volume carried by the fluid [m³].
double suspendedSediment(const World& w);
/// Sediment-weighted centre of the particles [m].
Eigen::Vector3d sedimentCentroid(const World& w);
/// Sediment-weighted variance about `about`, per axis [m²].
Eigen::Vector3d sedimentVariance(const World& w, const Eigen::Vector3d& about);
/// Least-squares slope of y against t over (t, y) samples (at least two distinct t).
double leastSquaresSlope(const std::vector<std::pair<double, double>>& samples);

}  // namespace scour
