// Where a node sits in its body, from the cells around it (docs/theory.md §3.5): the fraction of
// the full angle around the node (2D) or of its two sides (1D) that its cells fill. 1 inside;
// below 1 on the boundary; between 1/2 and 1 in 2D at a re-entrant corner (the toe of a cut),
// where the cells surround the node on more than a half-plane. Mirror planes through a node
// double its fraction once per plane (their image cells fill the other side).
#pragma once

#include <cstddef>

#include "rktsph/core/point_cloud.hpp"
#include "rktsph/mesh/cell_complex.hpp"

namespace rktsph {

enum class NodePlace {
  Isolated,         ///< in no cell: nothing moves it
  Interior,         ///< the cells fill the whole angle around it
  Boundary,         ///< on a face or at a convex corner
  ReentrantCorner,  ///< 2D, cells on more than a half-plane but not all round
};

/// The fraction of the angle around `node` that its cells fill, on the configuration `nodes`.
double filled_fraction(const CellComplex& cells, const PointCloud& nodes, std::size_t node);

/// The place of a node whose cells (with their mirror images) fill `fraction` of its angle.
NodePlace node_place(double fraction, int dimension);

/// The place of `node` on the configuration `nodes`, with a mirror plane through it for every bit
/// of `mirror_axes` (the images of its cells double its fraction once per plane).
NodePlace place_of_node(const CellComplex& cells, const PointCloud& nodes, std::size_t node,
                        unsigned mirror_axes);

}  // namespace rktsph
