#include "rktsph/geometry/crowded_nodes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "rktsph/mesh/polygon_distance.hpp"

namespace rktsph {

namespace {

// A node is not moved nearer a body than this fraction of its spacing: the contact tolerance
// (boundary_conditions.cpp, kBodyContactTolerance), inside which it would touch it.
constexpr double kSolidClearance = 0.02;

/// The distance from (x, y) to the nearest of `neighbours` at `x_now`, `y_now`.
double nearest_distance(double x, double y, std::span<const std::int32_t> neighbours,
                        const std::vector<double>& x_now, const std::vector<double>& y_now) {
  double nearest = std::numeric_limits<double>::infinity();
  for (std::int32_t j : neighbours) {
    const auto k = static_cast<std::size_t>(j);
    nearest = std::min(nearest, std::hypot(x - x_now[k], y - y_now[k]));
  }
  return nearest;
}

}  // namespace

std::size_t spread_crowded_nodes(const CellComplex& cells, const Outline& outline,
                                 const PointCloud& positions, std::span<const double> spacing,
                                 double fraction, std::span<const std::uint8_t> held_axes,
                                 std::span<const std::vector<Vec3>> solids, FieldArray& shift) {
  const std::size_t n = positions.size();
  std::fill(shift.data().begin(), shift.data().end(), 0.0);
  // The nodes move one after the other, each from where the ones before it went: moved all at
  // once from the old positions, two neighbouring surface nodes could swap onto one point (the
  // footing under a load, t = 5.33 s, §9.19).
  std::vector<double> x = positions.position[0], y = positions.position[1];
  std::vector<std::int32_t> neighbours;
  std::size_t moved = 0;
  for (std::size_t i = 0; i < n; ++i) {
    neighbours.clear();
    for (std::int32_t cell : cells.cells_of(i))
      for (std::int32_t corner : cells.corners(static_cast<std::size_t>(cell)))
        if (static_cast<std::size_t>(corner) != i) neighbours.push_back(corner);
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
    if (neighbours.empty()) continue;
    const double nearest = nearest_distance(x[i], y[i], neighbours, x, y);
    if (!(nearest < fraction * spacing[i])) continue;
    // Inside: the centroid of the neighbours; on the outline: the midpoint of the two neighbours
    // along it, so that a straight surface stays where it is.
    const std::span<const std::int32_t> facets = outline.facets_at(i);
    double target[2] = {0.0, 0.0};
    if (facets.empty()) {
      for (std::int32_t j : neighbours) {
        target[0] += x[static_cast<std::size_t>(j)];
        target[1] += y[static_cast<std::size_t>(j)];
      }
      for (double& coordinate : target)
        coordinate /= static_cast<double>(neighbours.size());
    } else if (facets.size() == 2) {
      for (std::int32_t f : facets) {
        const auto j = static_cast<std::size_t>(
            outline.other_node(static_cast<std::size_t>(f), static_cast<std::int32_t>(i)));
        target[0] += 0.5 * x[j];
        target[1] += 0.5 * y[j];
      }
    } else {
      continue;
    }
    if ((held_axes[i] >> 0) & 1u) target[0] = x[i];
    if ((held_axes[i] >> 1) & 1u) target[1] = y[i];
    // A move is made only if it takes the node farther from its nearest neighbour, which is what
    // it is for; and not into a body: the midpoint of two outline neighbours either side of a
    // body's corner lies inside it (§9.18).
    if (!(nearest_distance(target[0], target[1], neighbours, x, y) > nearest)) continue;
    const bool into_solid = std::any_of(solids.begin(), solids.end(), [&](const auto& solid) {
      return polygon_distance(solid, target[0], target[1]).depth > -kSolidClearance * spacing[i];
    });
    if (into_solid) continue;
    x[i] = target[0];
    y[i] = target[1];
    shift(0, i) = x[i] - positions.position[0][i];
    shift(1, i) = y[i] - positions.position[1][i];
    ++moved;
  }
  return moved;
}

}  // namespace rktsph
