#include "rktsph/simulation/case_warnings.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "rktsph/geometry/shapes.hpp"
#include "rktsph/mesh/cell_geometry.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph {

std::optional<CaseWarning> narrow_cell_warning(const NodeSets& nodes, const GeometrySpec& geometry,
                                               double time_step) {
  const CellComplex& cells = nodes.cells;
  if (nodes.on_lattice() || cells.cell_count() < 2) return std::nullopt;
  std::vector<double> widths(cells.cell_count());
  for (std::size_t p = 0; p < widths.size(); ++p)
    widths[p] = cell_width(cells.kind(p), cells.corner_positions(nodes.sph_nodes, p));
  const auto narrowest = std::min_element(widths.begin(), widths.end());
  const auto p = static_cast<std::size_t>(narrowest - widths.begin());
  const double smallest = *narrowest;
  std::vector<double> sorted = widths;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  const double median = sorted[sorted.size() / 2];
  if (!(smallest * kNarrowCellRatio <= median)) return std::nullopt;
  const auto centre = cell_centroid(cells.kind(p), cells.corner_positions(nodes.sph_nodes, p));
  const bool mesh_file = !geometry.mesh.empty();
  // At the shape the cell lies in (the last covering it, as for its material), or the mesh key.
  const int shape =
      mesh_file ? -1
                : covering_shape(geometry, nodes.dimension, {centre[0], centre[1], centre[2]},
                                 kSpacingTolerance * nodes.spacing);
  return CaseWarning{
      mesh_file
          ? geometry.mesh_where
          : (shape >= 0 ? geometry.shapes[static_cast<std::size_t>(shape)].where : geometry.where),
      mesh_file ? "geometry.mesh" : "geometry.shapes",
      fmt::format("the {} at ({:.4g}, {:.4g})", kind_name(cells.kind(p)), centre[0], centre[1]),
      fmt::format("is {:.1f} times narrower than the median cell ({:.3g} m against {:.3g} m) and "
                  "sets the time step (dt = {:.3g} s): the run takes about {:.0f} times the steps "
                  "the rest of the mesh needs. {}",
                  median / smallest, smallest, median, time_step, median / smallest,
                  mesh_file ? "Remesh around it (a size field, or no short curve or close points "
                              "there in the .geo) if that is not meant"
                            : "A short shape edge or two vertices close together make it; move "
                              "them apart if that is not meant")};
}

std::optional<CaseWarning> formed_cells_stiffness_warning(const Simulation& simulation) {
  const NumericsSpec& numerics = simulation.description().numerics;
  if (!simulation.assembly().forms_cells() || !numerics.hourglass_stiffness ||
      !(*numerics.hourglass_stiffness > 0.0))
    return std::nullopt;
  return CaseWarning{
      numerics.where, "numerics.hourglass.stiffness",
      fmt::format("{}", *numerics.hourglass_stiffness),
      "acts on the hourglass modes of quadrilaterals, and with numerics.cells.policy: reformed the "
      "cells are triangles formed from the nodes: it does not act; the patch stiffness "
      "(numerics.hourglass.patch_stiffness) controls the triangles' soft modes (docs/theory.md "
      "§9.17)"};
}

std::vector<CaseWarning> case_warnings(const Simulation& simulation) {
  std::vector<CaseWarning> warnings =
      plausibility_warnings(simulation.description(), simulation.time_step());
  if (auto stiffness = formed_cells_stiffness_warning(simulation))
    warnings.push_back(std::move(*stiffness));
  // Only a Courant step follows the narrowest cell; a fixed numerics.time_step does not.
  if (simulation.description().numerics.time_step) return warnings;
  if (auto narrow = narrow_cell_warning(simulation.nodes(), simulation.description().geometry,
                                        simulation.time_step()))
    warnings.push_back(std::move(*narrow));
  return warnings;
}

}  // namespace rktsph
