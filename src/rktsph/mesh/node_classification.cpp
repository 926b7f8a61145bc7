#include "rktsph/mesh/node_classification.hpp"

#include <bit>
#include <cmath>
#include <numbers>

namespace rktsph {

namespace {

// Fractions are sums of corner angles over 2 pi: exact multiples of 1/4 on a lattice, rounding
// elsewhere; this separates "full" from "almost full" on any mesh a mesher accepts.
constexpr double kFractionTolerance = 1e-9;

}  // namespace

double filled_fraction(const CellComplex& cells, const PointCloud& nodes, std::size_t node) {
  double fraction = 0.0;
  for (const std::int32_t p : cells.cells_of(node)) {
    const auto cell = static_cast<std::size_t>(p);
    if (cells.dimension() < 2) {
      fraction += 0.5;
      continue;
    }
    const auto corners = cells.corners(cell);
    const int n = static_cast<int>(corners.size());
    int k = 0;
    while (corners[static_cast<std::size_t>(k)] != static_cast<std::int32_t>(node))
      ++k;
    const auto at = static_cast<std::size_t>(corners[static_cast<std::size_t>(k)]);
    const auto next = static_cast<std::size_t>(corners[static_cast<std::size_t>((k + 1) % n)]);
    const auto previous =
        static_cast<std::size_t>(corners[static_cast<std::size_t>((k + n - 1) % n)]);
    const double ax = nodes.position[0][next] - nodes.position[0][at];
    const double ay = nodes.position[1][next] - nodes.position[1][at];
    const double bx = nodes.position[0][previous] - nodes.position[0][at];
    const double by = nodes.position[1][previous] - nodes.position[1][at];
    fraction += std::atan2(ax * by - ay * bx, ax * bx + ay * by) / (2.0 * std::numbers::pi);
  }
  return fraction;
}

NodePlace place_of_node(const CellComplex& cells, const PointCloud& nodes, std::size_t node,
                        unsigned mirror_axes) {
  const double images = static_cast<double>(1u << std::popcount(mirror_axes));
  return node_place(filled_fraction(cells, nodes, node) * images, cells.dimension());
}

NodePlace node_place(double fraction, int dimension) {
  if (fraction <= kFractionTolerance) return NodePlace::Isolated;
  if (fraction >= 1.0 - kFractionTolerance) return NodePlace::Interior;
  if (dimension >= 2 && fraction > 0.5 + kFractionTolerance) return NodePlace::ReentrantCorner;
  return NodePlace::Boundary;
}

}  // namespace rktsph
