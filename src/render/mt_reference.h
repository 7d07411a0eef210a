#pragma once
// Marching tetrahedra on the CPU: the same cut, the same interpolation and orientation as
// shaders/march.glsl, over every cell. The tests check the GPU surface against it.
#include <vector>

#include "render/surface.h"

namespace scour {

std::vector<SurfaceTriangle> marchTetrahedraCpu(const DensityGrid& grid, double iso);

}  // namespace scour
