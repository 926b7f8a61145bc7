// A 1D cell: two nodes, left to right; its stress point at the mid-point (docs/theory.md §3.5).
#pragma once

#include <array>

#include "rktsph/mesh/cell_kinds/cell_corners.hpp"

namespace rktsph::segment {

inline constexpr std::array<CellFace, 2> kFaces{{{1, {0, 0}}, {1, {1, 0}}}};

/// Signed length: negative when the nodes have crossed.
inline double measure(const CellCorners& c) {
  return c.x[1] - c.x[0];
}

inline std::array<double, 3> centroid(const CellCorners& c) {
  return {(c.x[0] + c.x[1]) / 2.0, 0.0, 0.0};
}

/// The one Jacobian of a segment, its length, at both ends.
inline void corner_jacobians(const CellCorners& c, std::array<double, kMaxCellCorners>& jacobian) {
  jacobian[0] = jacobian[1] = measure(c);
}

/// Its length [m].
inline double width(const CellCorners& c) {
  return std::abs(measure(c));
}

/// 1 for a segment of positive length, -1 for a crossed one.
inline double quality(const CellCorners& c) {
  return measure(c) > 0.0 ? 1.0 : -1.0;
}

}  // namespace rktsph::segment
