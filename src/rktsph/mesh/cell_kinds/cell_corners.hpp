// The corner coordinates of one cell, gathered once from the node positions so that each kind's
// formulas read plain numbers (docs/theory.md §3.5).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>

#include "rktsph/core/point_cloud.hpp"
#include "rktsph/mesh/cell_kind.hpp"

namespace rktsph {

struct CellCorners {
  int count = 0;
  std::array<double, kMaxCellCorners> x{};
  std::array<double, kMaxCellCorners> y{};  ///< 0 in 1D
};

/// A face of a cell: the local indices of its corners (one in 1D, two in 2D), ordered so that the
/// cell lies on the left of the directed edge in 2D.
struct CellFace {
  int count = 0;
  std::array<int, 2> corner{};
};

inline CellCorners gather_corners(const PointCloud& nodes, std::span<const std::int32_t> corners) {
  CellCorners c;
  c.count = static_cast<int>(corners.size());
  for (int k = 0; k < c.count; ++k) {
    const auto node = static_cast<std::size_t>(corners[static_cast<std::size_t>(k)]);
    c.x[static_cast<std::size_t>(k)] = nodes.position[0][node];
    c.y[static_cast<std::size_t>(k)] = nodes.dimension >= 2 ? nodes.position[1][node] : 0.0;
  }
  return c;
}

/// The corner Jacobians of a polygon with counter-clockwise corners: the cross product of the
/// two edges leaving each corner (to the next corner, then to the previous one), positive at a
/// convex corner of an unfolded cell.
inline void polygon_corner_jacobians(const CellCorners& c,
                                     std::array<double, kMaxCellCorners>& jacobian) {
  const int n = c.count;
  for (int k = 0; k < n; ++k) {
    const auto at = static_cast<std::size_t>(k);
    const auto next = static_cast<std::size_t>((k + 1) % n);
    const auto previous = static_cast<std::size_t>((k + n - 1) % n);
    const double ax = c.x[next] - c.x[at], ay = c.y[next] - c.y[at];
    const double bx = c.x[previous] - c.x[at], by = c.y[previous] - c.y[at];
    jacobian[at] = ax * by - ay * bx;
  }
}

/// The smallest corner's sine of a counter-clockwise polygon, J_k / (|e_next| |e_prev|): 1 at a
/// right angle, towards 0 as a corner closes or opens flat, negative at a re-entrant or inverted
/// corner. A corner with a zero-length edge counts as 0.
inline double polygon_smallest_corner_sine(const CellCorners& c) {
  std::array<double, kMaxCellCorners> jacobian{};
  polygon_corner_jacobians(c, jacobian);
  const int n = c.count;
  double smallest = 1.0;
  for (int k = 0; k < n; ++k) {
    const auto at = static_cast<std::size_t>(k);
    const auto next = static_cast<std::size_t>((k + 1) % n);
    const auto previous = static_cast<std::size_t>((k + n - 1) % n);
    const double a = std::hypot(c.x[next] - c.x[at], c.y[next] - c.y[at]);
    const double b = std::hypot(c.x[previous] - c.x[at], c.y[previous] - c.y[at]);
    smallest = std::min(smallest, a * b > 0.0 ? jacobian[at] / (a * b) : 0.0);
  }
  return smallest;
}

/// The longest edge of a polygon [m].
inline double polygon_longest_edge(const CellCorners& c) {
  double longest = 0.0;
  for (int k = 0; k < c.count; ++k) {
    const auto at = static_cast<std::size_t>(k);
    const auto next = static_cast<std::size_t>((k + 1) % c.count);
    longest = std::max(longest, std::hypot(c.x[next] - c.x[at], c.y[next] - c.y[at]));
  }
  return longest;
}

}  // namespace rktsph
