// Stencils from the cells instead of from a radius (docs/theory.md §4.8): on cells other than a
// lattice's squares a radius cannot pick a cell's corners and nothing else (an obtuse triangle's
// neighbour apex can lie nearer its centroid than its own corners), so the rows of the step are
// made from the complex: a stress point sees its cell's corners, a node the centroids of its
// cells, a boundary node its cells' other corners; a node on a mirror plane also sees the images
// of its sources across it. Each row then has its own smoothing length, a fixed multiple of the
// distance to its farthest source: on a square lattice these are the stencils and the smoothing
// length of the radius search at h = h_over_dx dx.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rktsph/core/point_cloud.hpp"
#include "rktsph/mesh/cell_complex.hpp"
#include "rktsph/sph/operators.hpp"

namespace rktsph {

/// What a row's stencil joins, which sets how far its farthest source lies on a lattice.
enum class CellStencilKind {
  CellCorners,     ///< a stress point and its cell's corners: sqrt(d)/2 dx on a lattice
  CellCentroids,   ///< a node and its cells' centroids: sqrt(d)/2 dx on a lattice
  CellNeighbours,  ///< a node and the other corners of its cells: sqrt(d) dx on a lattice
};

/// The row's smoothing length (docs/theory.md eq. 4.9): h_over_dx times the distance from
/// `target` to its farthest source over that distance on a lattice in units of dx.
double cell_stencil_smoothing_length(const std::array<double, 3>& target,
                                     std::span<const StencilSource> stencil, int dimension,
                                     double h_over_dx, CellStencilKind kind);

/// The corners of cell `cell` at their positions in `nodes`, columns = node indices.
void gather_cell_corners(const CellComplex& cells, const PointCloud& nodes, std::size_t cell,
                         std::vector<StencilSource>& stencil);

/// The centroids (positions in `points`) of the cells of node `node`, columns = cell indices,
/// with their images across every mirror plane through the node (`mirrors`, a plane being through
/// the node when the node lies within `tolerance` [m] of it).
void gather_cell_centroids(const CellComplex& cells, const PointCloud& nodes,
                           const PointCloud& points, std::size_t node,
                           std::span<const MirrorPlane> mirrors, double tolerance,
                           std::vector<StencilSource>& stencil);

/// The other corners of the cells of node `node` (each once, by increasing index; columns = node
/// indices), with the images of those off the planes across every mirror plane through the node.
void gather_cell_neighbours(const CellComplex& cells, const PointCloud& nodes, std::size_t node,
                            std::span<const MirrorPlane> mirrors, double tolerance,
                            std::vector<StencilSource>& stencil);

/// Each point's smoothing length (eq. 4.9) from the cells: a stress point's of its cell's corners,
/// a node's of its cells' centroids, at the positions of `nodes` and `points`.
void cell_smoothing_lengths(const CellComplex& cells, const PointCloud& nodes,
                            const PointCloud& points, double h_over_dx,
                            std::vector<double>& node_smoothing_length,
                            std::vector<double>& point_smoothing_length);

}  // namespace rktsph
