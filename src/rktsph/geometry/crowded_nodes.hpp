// Nodes that crowd together in a flow, spread before the cells are formed again (issue 29;
// docs/theory.md §9.19): the particle shifting of particle-FE codes (the Laplacian smoothing of
// ESPFEM2D, Zhang et al. 2024), which moves a node without moving its fields.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rktsph/core/field_array.hpp"
#include "rktsph/core/point_cloud.hpp"
#include "rktsph/core/small_tensor.hpp"
#include "rktsph/mesh/cell_complex.hpp"
#include "rktsph/mesh/outline.hpp"

namespace rktsph {

/// For every node whose nearest neighbour in `cells` at `positions` is closer than `fraction`
/// times its `spacing`, the move (into `shift`, one field per axis; zero elsewhere) that takes it
/// to the centroid of its neighbours in the cells, or, on the outline, to the midpoint of its two
/// neighbours along it (eq. 9.16); in the order of the nodes, each from where the ones before it
/// went. Components whose bit is set in `held_axes[node]` (an imposed velocity) and outline nodes
/// without exactly two outline neighbours are not moved, nor is a node whose move would not take
/// it farther from its nearest neighbour, or would end inside one of the `solids` (rigid bodies'
/// outlines) or within 0.02 of its spacing of one. Returns how many nodes move. 2D.
std::size_t spread_crowded_nodes(const CellComplex& cells, const Outline& outline,
                                 const PointCloud& positions, std::span<const double> spacing,
                                 double fraction, std::span<const std::uint8_t> held_axes,
                                 std::span<const std::vector<Vec3>> solids, FieldArray& shift);

}  // namespace rktsph
