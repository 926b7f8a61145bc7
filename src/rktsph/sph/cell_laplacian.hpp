// The pore-pressure operators from the cells, for nodes that are not on a lattice (docs/theory.md
// §6.3, eqs. 6.6-6.7). On a triangle mesh the Morris Laplacian of laplacian.hpp has no consistency
// scale that fits (its scale is computed for a square lattice of spacing dx, and the nodes lie at
// uneven distances, about 0.7 dx apart), so the pressure solve takes the linear finite-element
// operators of the triangles instead:
//
//   Ltilde_ij = -scale * sum_T A_T grad(phi_i).grad(phi_j)   (the P1 stiffness, negated)   (6.6)
//   V_eff,i   = sum_T A_T / 3                                 (the lumped node volume)
//   (grad f)_i = (1 / V_eff,i) sum_T (A_T / 3) grad(f_T)      (the lumped cell gradient)    (6.7)
//
// with phi_i the hat function of node i and f_T the linear interpolant of f on triangle T. The
// matrix is symmetric and negative semi-definite with rows summing to zero; its natural boundary
// condition is zero flux, which is what both an impermeable face and a mirror plane ask for, so no
// images are folded in and no volume is halved (a node on a mirror plane has only its physical
// triangles, which is already the half its mirrored patch would have). (6.7) is the lumped average
// the step advances the skeleton's strain with on triangles (eq. 2.5), so the pressure equation
// sees the volumetric strain rate the effective stress sees.
#pragma once

#include "rktsph/core/point_cloud.hpp"
#include "rktsph/mesh/cell_complex.hpp"
#include "rktsph/sph/laplacian.hpp"
#include "rktsph/sph/operators.hpp"

namespace rktsph {

/// Ltilde and V_eff of eq. 6.6 on the cells of `cells` at the positions `nodes`; `scale` > 0
/// multiplies the operator (1, its consistent value, otherwise). Every cell must be a triangle
/// (std::invalid_argument otherwise).
LaplacianMatrix build_cell_laplacian(const CellComplex& cells, const PointCloud& nodes,
                                     double scale);

/// The collocated gradient of eq. 6.7 as a weight table over the nodes (row i: the corners of the
/// triangles of node i, itself included, with interpolation weight 1 on itself and 0 elsewhere; no
/// mirror images). Every cell must be a triangle (std::invalid_argument otherwise).
WeightTable build_cell_node_gradient(const CellComplex& cells, const PointCloud& nodes);

}  // namespace rktsph
