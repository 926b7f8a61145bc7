// A square lattice of points for the benchmarks: the SPH nodes of the small-deformation layout
// (docs/theory.md §3.1) or, offset by half a spacing, its stress points.
#pragma once

#include <cstddef>

#include "rktsph/core/point_cloud.hpp"

namespace rktsph::bench {

/// `per_side` x `per_side` points of spacing `spacing`, the first at (start, start).
inline PointCloud square_lattice(int per_side, double spacing, double start) {
  PointCloud cloud;
  cloud.dimension = 2;
  cloud.resize(static_cast<std::size_t>(per_side) * per_side);
  for (int j = 0; j < per_side; ++j) {
    for (int i = 0; i < per_side; ++i) {
      const std::size_t index = static_cast<std::size_t>(j) * per_side + i;
      cloud.position[0][index] = start + i * spacing;
      cloud.position[1][index] = start + j * spacing;
      cloud.volume[index] = spacing * spacing;
    }
  }
  return cloud;
}

}  // namespace rktsph::bench
