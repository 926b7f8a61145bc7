// Cells formed from a cloud of nodes where they are now (issue 29; docs/theory.md §3.9): the
// Delaunay triangulation of the nodes' positions, trimmed by an alpha criterion so that cells
// spanning a gap of the body (a notch, a crack, two bodies apart) are not kept. This is the first
// brick of the configuration policy that forms cells again as a body flows; no step calls it yet.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "rktsph/core/point_cloud.hpp"
#include "rktsph/core/small_tensor.hpp"
#include "rktsph/mesh/cell_complex.hpp"

namespace rktsph {

/// What forming the cells did: the Delaunay triangles, those the alpha criterion dropped, and the
/// nodes left in no kept cell (they carry no volume until cells form around them again).
struct DelaunayCellCount {
  std::size_t triangles = 0;
  std::size_t dropped = 0;
  /// Dropped triangles kept again so that every node has one fan of cells (a manifold outline).
  std::size_t restored = 0;
  std::size_t isolated_nodes = 0;
};

struct DelaunayCells {
  CellComplex cells;  ///< over every node of the cloud, reference measures from these positions
  DelaunayCellCount count;
};

/// The triangles of the Delaunay triangulation of `nodes` (2D) whose circumradius is at most
/// `alpha` times the mean `spacing` of their corners (eq. 3.15): on a square lattice of spacing dx
/// every cell has R = dx/sqrt(2), so alpha >= 1/sqrt(2) keeps a lattice whole. A kept cell's
/// material is that of at least two of its corners (`node_material`), else that of its first
/// corner in node order. Where the kept triangles around a node form two fans or more (two
/// parts of the body touching at a node), the dropped ones of the smallest inner gap are kept
/// again until it has one, so that the outline passes each node once. Fewer than three nodes, or
/// all on a line, give no cell. Throws std::invalid_argument for a cloud that is not 2D, spans of
/// the wrong length, an alpha or a spacing that is not a positive number, and two nodes at one
/// position.
/// With `every_node_in_a_cell`, a node the criterion leaves in no cell first keeps the Delaunay
/// triangle at it with the smallest circumradius (counted as restored), so that no node is left
/// out of the body.
/// A triangle whose centroid or an edge's midpoint lies inside one of the `solids` (simple
/// polygons, e.g. rigid bodies, docs/theory.md §9.18) is dropped and never kept again by either
/// repair: no cell crosses a solid.
DelaunayCells delaunay_cells(const PointCloud& nodes, std::span<const double> spacing,
                             std::span<const std::int32_t> node_material, double alpha,
                             bool every_node_in_a_cell = false,
                             std::span<const std::vector<Vec3>> solids = {});

}  // namespace rktsph
