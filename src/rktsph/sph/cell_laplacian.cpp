#include "rktsph/sph/cell_laplacian.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <vector>

#include "rktsph/mesh/cell_kinds/triangle.hpp"

namespace rktsph {

namespace {

using Vector2 = std::array<double, 2>;

/// A triangle's area and the gradients of its three hat functions (constant on it).
struct TriangleGradients {
  double area = 0.0;
  std::array<Vector2, 3> gradient{};
};

// grad(phi_k) = (y_{k+1} - y_{k+2}, x_{k+2} - x_{k+1}) / (2A) for counter-clockwise corners: the
// inward normal of the opposite edge over the altitude from corner k.
TriangleGradients triangle_gradients(const CellComplex& cells, const PointCloud& nodes,
                                     std::size_t cell) {
  if (cells.kind(cell) != CellKind::Triangle)
    throw std::invalid_argument(
        fmt::format("the cell pore-pressure operators need triangles; cell {} is a {}", cell,
                    kind_name(cells.kind(cell))));
  const CellCorners c = cells.corner_positions(nodes, cell);
  TriangleGradients result;
  result.area = triangle::measure(c);
  if (!(result.area > 0.0))
    throw std::invalid_argument(
        fmt::format("the cell pore-pressure operators: cell {} has area {}", cell, result.area));
  const double inverse = 0.5 / result.area;
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t next = (k + 1) % 3, other = (k + 2) % 3;
    result.gradient[k] = {(c.y[next] - c.y[other]) * inverse, (c.x[other] - c.x[next]) * inverse};
  }
  return result;
}

double dot(const Vector2& a, const Vector2& b) {
  return a[0] * b[0] + a[1] * b[1];
}

}  // namespace

LaplacianMatrix build_cell_laplacian(const CellComplex& cells, const PointCloud& nodes,
                                     double scale) {
  const std::size_t n = nodes.size();
  LaplacianMatrix result;
  result.scale = scale > 0.0 ? scale : 1.0;
  result.effective_volume.assign(n, 0.0);
  std::vector<double> diagonal(n, 0.0);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(6 * cells.cell_count() + n);
  for (std::size_t p = 0; p < cells.cell_count(); ++p) {
    const TriangleGradients triangle = triangle_gradients(cells, nodes, p);
    const auto corners = cells.corners(p);
    for (std::size_t k = 0; k < 3; ++k) {
      const auto i = static_cast<std::size_t>(corners[k]);
      const auto j = static_cast<std::size_t>(corners[(k + 1) % 3]);
      result.effective_volume[i] += triangle.area / 3.0;
      // One value for (i, j) and (j, i), so that Ltilde is symmetric to the last bit; the diagonal
      // is minus the row's off-diagonal sum, so that a constant has zero Laplacian (Σ_j grad
      // phi_j = 0) and the solve conserves water (eq. 6.6).
      const double coupling =
          result.scale * triangle.area * dot(triangle.gradient[k], triangle.gradient[(k + 1) % 3]);
      entries.emplace_back(static_cast<int>(i), static_cast<int>(j), -coupling);
      entries.emplace_back(static_cast<int>(j), static_cast<int>(i), -coupling);
      diagonal[i] += coupling;
      diagonal[j] += coupling;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    entries.emplace_back(static_cast<int>(i), static_cast<int>(i), diagonal[i]);
  result.weighted.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  result.weighted.setFromTriplets(entries.begin(), entries.end());
  return result;
}

WeightTable build_cell_node_gradient(const CellComplex& cells, const PointCloud& nodes) {
  WeightTable table;
  table.dimension = 2;
  table.row_start.assign(1, 0);
  std::vector<std::int32_t> columns;
  std::vector<Vector2> weights;
  for (std::size_t node = 0; node < nodes.size(); ++node) {
    columns.clear();
    weights.clear();
    double volume = 0.0;
    for (const std::int32_t cell : cells.cells_of(node)) {
      const TriangleGradients triangle =
          triangle_gradients(cells, nodes, static_cast<std::size_t>(cell));
      const auto corners = cells.corners(static_cast<std::size_t>(cell));
      volume += triangle.area / 3.0;
      for (std::size_t k = 0; k < 3; ++k) {
        const auto found = std::find(columns.begin(), columns.end(), corners[k]);
        const auto slot = static_cast<std::size_t>(found - columns.begin());
        if (found == columns.end()) {
          columns.push_back(corners[k]);
          weights.push_back({0.0, 0.0});
        }
        for (std::size_t a = 0; a < 2; ++a)
          weights[slot][a] += triangle.area / 3.0 * triangle.gradient[k][a];
      }
    }
    if (!(volume > 0.0))
      throw std::invalid_argument(
          fmt::format("the cell pore-pressure gradient: node {} is in no cell", node));
    for (std::size_t slot = 0; slot < columns.size(); ++slot) {
      table.source.push_back(columns[slot]);
      table.reflection.push_back(0);
      table.interpolation.push_back(static_cast<std::size_t>(columns[slot]) == node ? 1.0 : 0.0);
      for (std::size_t a = 0; a < 2; ++a)
        table.gradient[a].push_back(weights[slot][a] / volume);
    }
    table.row_start.push_back(static_cast<std::int64_t>(table.source.size()));
  }
  return table;
}

}  // namespace rktsph
