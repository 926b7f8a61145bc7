// What every cell kind supplies, dispatched on the kind (docs/theory.md §3.5): the one place a
// caller asks a cell for its measure, centroid, corner Jacobians, faces and quality, whatever
// its shape.
#pragma once

#include <array>
#include <span>

#include "rktsph/mesh/cell_complex.hpp"
#include "rktsph/mesh/cell_kind.hpp"
#include "rktsph/mesh/cell_kinds/cell_corners.hpp"

namespace rktsph {

/// Signed length (1D) or area (2D) [m^d]; not positive once the cell is inverted.
double cell_measure(CellKind kind, const CellCorners& corners);

/// The cell's stress-point position: the mean of its corners.
std::array<double, 3> cell_centroid(CellKind kind, const CellCorners& corners);

/// The Jacobian at each corner (its first corner_count(kind) entries).
void cell_corner_jacobians(CellKind kind, const CellCorners& corners,
                           std::array<double, kMaxCellCorners>& jacobian);

/// The faces of a cell of `kind` in local corner indices, the cell on their left (2D).
std::span<const CellFace> cell_faces(CellKind kind);

/// The smallest altitude [m] (a triangle's 2A over its longest edge, a quadrilateral's A over its
/// longest edge, a segment's length): the length a wave crosses the cell in, which sets the
/// time step (docs/theory.md §2.5).
double cell_width(CellKind kind, const CellCorners& corners);

/// The smallest cell_width of a complex's cells at the positions `nodes` [m].
double smallest_cell_width(const CellComplex& cells, const PointCloud& nodes);

/// A shape measure independent of size: the smallest corner's sine in 2D (1 for a square, sqrt(3)/2
/// for an equilateral triangle), 1 for a segment; not positive once a corner folds.
double cell_quality(CellKind kind, const CellCorners& corners);

}  // namespace rktsph
