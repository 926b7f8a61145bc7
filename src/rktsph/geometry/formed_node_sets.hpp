// Node sets whose cells are formed again from the nodes where they are now (issue 29;
// docs/theory.md §9.17): the same nodes, materials and masses as the start's, and the Delaunay
// cells of their current positions trimmed by the alpha criterion (eq. 3.15), with the stress
// points at the cells' centroids. The step integrates over them as over a fresh mesh; the
// displacement stays measured from the start.
#pragma once

#include <span>

#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/mesh/delaunay_cells.hpp"

namespace rktsph {

struct FormedNodeSets {
  NodeSets nodes;
  DelaunayCellCount count;
};

/// The nodes of `start` at the positions `current`, with the Delaunay cells of those positions
/// whose circumradius is at most `alpha` times their corners' mean `spacing` (eq. 3.15), every
/// node kept in a cell and with one fan of cells (delaunay_cells' repairs, §9.17):
/// - the nodes at `current`, with `start`'s volumes: their masses over their reference
///   densities, which no forming changes (eq. 9.11);
/// - the cells' reference measures, outline and normals those of `current`;
/// - stress point p at cell p's centroid, its volume the cell's area times the mean over its
///   corners of V_0/V (V a corner's volume in `current`): so that V/V_0 of the point, which
///   weighs its momentum rate (eq. 9.3), starts at its corners' mean (eq. 9.12).
/// No cell crosses one of the `solids` (the rigid bodies where they are, §9.18).
FormedNodeSets form_node_sets(const NodeSets& start, const PointCloud& current,
                              std::span<const double> spacing, double alpha,
                              std::span<const std::vector<Vec3>> solids = {});

}  // namespace rktsph
