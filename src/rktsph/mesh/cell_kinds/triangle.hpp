// A linear triangle: three nodes counter-clockwise; its stress point at the centroid, where the
// mean of the corners is exact (docs/theory.md §3.5).
#pragma once

#include <array>

#include "rktsph/mesh/cell_kinds/cell_corners.hpp"

namespace rktsph::triangle {

inline constexpr std::array<CellFace, 3> kFaces{{{2, {0, 1}}, {2, {1, 2}}, {2, {2, 0}}}};

/// Signed area: negative when the corners turn clockwise (an inverted triangle).
inline double measure(const CellCorners& c) {
  return 0.5 * ((c.x[1] - c.x[0]) * (c.y[2] - c.y[0]) - (c.x[2] - c.x[0]) * (c.y[1] - c.y[0]));
}

inline std::array<double, 3> centroid(const CellCorners& c) {
  return {(c.x[0] + c.x[1] + c.x[2]) / 3.0, (c.y[0] + c.y[1] + c.y[2]) / 3.0, 0.0};
}

inline void corner_jacobians(const CellCorners& c, std::array<double, kMaxCellCorners>& jacobian) {
  polygon_corner_jacobians(c, jacobian);
}

/// The smallest altitude, 2 A / (longest edge) [m]: the distance a wave crosses the cell in.
inline double width(const CellCorners& c) {
  const double longest = polygon_longest_edge(c);
  return longest > 0.0 ? 2.0 * std::abs(measure(c)) / longest : 0.0;
}

/// The smallest corner's sine, J_k / (|e_next| |e_prev|): sqrt(3)/2 for an equilateral triangle,
/// towards 0 as a corner closes or opens flat, negative once inverted.
inline double quality(const CellCorners& c) {
  return polygon_smallest_corner_sine(c);
}

}  // namespace rktsph::triangle
