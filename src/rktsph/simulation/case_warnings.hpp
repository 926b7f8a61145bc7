// The warnings of a case once its run is put together (docs/input-reference.md, "Plausibility
// warnings"): those of its values (case/plausibility.hpp) and those of its mesh, which only the
// built cells can give.
#pragma once

#include <optional>
#include <vector>

#include "rktsph/case/plausibility.hpp"
#include "rktsph/geometry/node_sets.hpp"

namespace rktsph {

class Simulation;

/// A cell of a mesh off a lattice is this many times narrower than the median cell, or more,
/// before it is named: the time step follows the narrowest cell (docs/theory.md §2.5, §4.8), so
/// the run then takes that many times the steps the rest of the mesh needs.
inline constexpr double kNarrowCellRatio = 5.0;

/// The narrowest cell of a mesh off a lattice, when it is kNarrowCellRatio or more times narrower
/// than the median cell: where it is, how much narrower, and what it costs. None on a lattice.
std::optional<CaseWarning> narrow_cell_warning(const NodeSets& nodes, const GeometrySpec& geometry,
                                               double time_step);

/// numerics.hourglass.stiffness given with cells formed again: it acts on quadrilaterals, and
/// formed cells are triangles (docs/theory.md §9.17). None otherwise.
std::optional<CaseWarning> formed_cells_stiffness_warning(const Simulation& simulation);

/// The case's plausibility warnings, the formed cells' and its mesh's, in that order.
std::vector<CaseWarning> case_warnings(const Simulation& simulation);

}  // namespace rktsph
