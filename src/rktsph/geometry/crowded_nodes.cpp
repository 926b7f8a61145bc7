#include "rktsph/geometry/crowded_nodes.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rktsph {

namespace {

double distance(const PointCloud& positions, std::size_t i, std::size_t j) {
  return std::hypot(positions.position[0][i] - positions.position[0][j],
                    positions.position[1][i] - positions.position[1][j]);
}

}  // namespace

std::size_t spread_crowded_nodes(const CellComplex& cells, const Outline& outline,
                                 const PointCloud& positions, std::span<const double> spacing,
                                 double fraction, std::span<const std::uint8_t> held_axes,
                                 FieldArray& shift) {
  const std::size_t n = positions.size();
  std::fill(shift.data().begin(), shift.data().end(), 0.0);
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
    double nearest = distance(positions, i, static_cast<std::size_t>(neighbours.front()));
    for (std::int32_t j : neighbours)
      nearest = std::min(nearest, distance(positions, i, static_cast<std::size_t>(j)));
    if (!(nearest < fraction * spacing[i])) continue;
    // Inside: the centroid of the neighbours; on the outline: the midpoint of the two neighbours
    // along it, so that a straight surface stays where it is.
    const std::span<const std::int32_t> facets = outline.facets_at(i);
    double target[2] = {0.0, 0.0};
    if (facets.empty()) {
      for (std::int32_t j : neighbours)
        for (std::size_t a = 0; a < 2; ++a)
          target[a] += positions.position[a][static_cast<std::size_t>(j)];
      for (double& x : target)
        x /= static_cast<double>(neighbours.size());
    } else if (facets.size() == 2) {
      for (std::int32_t f : facets) {
        const auto j = static_cast<std::size_t>(
            outline.other_node(static_cast<std::size_t>(f), static_cast<std::int32_t>(i)));
        for (std::size_t a = 0; a < 2; ++a)
          target[a] += 0.5 * positions.position[a][j];
      }
    } else {
      continue;
    }
    bool moves = false;
    for (std::size_t a = 0; a < 2; ++a) {
      if ((held_axes[i] >> a) & 1u) continue;
      shift(static_cast<int>(a), i) = target[a] - positions.position[a][i];
      moves = moves || shift(static_cast<int>(a), i) != 0.0;
    }
    if (moves) ++moved;
  }
  return moved;
}

}  // namespace rktsph
