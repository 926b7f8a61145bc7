// A bilinear quadrilateral: four nodes counter-clockwise; its stress point at the mean of its
// corners, which is where a lattice cell's centre is (docs/theory.md §3.5).
#pragma once

#include <array>

#include "rktsph/mesh/cell_kinds/cell_corners.hpp"

namespace rktsph::quadrilateral {

inline constexpr std::array<CellFace, 4> kFaces{
    {{2, {0, 1}}, {2, {1, 2}}, {2, {2, 3}}, {2, {3, 0}}}};

/// Signed area: half the cross product of the diagonals, exact for any non-self-intersecting
/// quadrilateral; negative when inverted.
inline double measure(const CellCorners& c) {
  const double ax = c.x[2] - c.x[0], ay = c.y[2] - c.y[0];
  const double bx = c.x[3] - c.x[1], by = c.y[3] - c.y[1];
  return 0.5 * (ax * by - ay * bx);
}

inline std::array<double, 3> centroid(const CellCorners& c) {
  double sx = 0.0, sy = 0.0;
  for (std::size_t k = 0; k < 4; ++k) {
    sx += c.x[k];
    sy += c.y[k];
  }
  return {sx / 4.0, sy / 4.0, 0.0};
}

inline void corner_jacobians(const CellCorners& c, std::array<double, kMaxCellCorners>& jacobian) {
  polygon_corner_jacobians(c, jacobian);
}

/// A / (longest edge) [m]: the smallest altitude of a parallelogram (dx on a lattice).
inline double width(const CellCorners& c) {
  const double longest = polygon_longest_edge(c);
  return longest > 0.0 ? std::abs(measure(c)) / longest : 0.0;
}

/// The smallest corner's sine, J_k / (|e_next| |e_prev|): 1 for a rectangle, 0 at a straight
/// corner, negative at a re-entrant (arrowhead) or inverted one.
inline double quality(const CellCorners& c) {
  return polygon_smallest_corner_sine(c);
}

}  // namespace rktsph::quadrilateral
