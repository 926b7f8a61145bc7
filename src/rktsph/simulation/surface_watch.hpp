// The free surface that the detector of docs/theory.md §9.4 finds on a run's current
// configuration, for the field output and the checks: the conditions of a moving body act on the
// perimeter of its cells (§9.7), and this says how well the detector agrees with it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rktsph/boundary/free_surface_detection.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph {

/// h of the detection over dx: inside the range its thresholds are calibrated for (1.0-1.5 dx),
/// whatever the step's own h.
inline constexpr double kDetectionSmoothingOverSpacing = 1.3;

/// Runs the detector on the SPH nodes of the run's current configuration (2D and 1D).
void detect_current_surface(const Simulation& simulation, FreeSurface& out);

/// The free surface as the cells draw it (docs/theory.md §9.17): the nodes the conditions project
/// traction-free (a facet with a free normal velocity), each with the unit sum of those facets'
/// current normals. Not the nodes where a velocity is imposed (a fixed base, a footing).
void outline_free_surface(const Simulation& simulation, FreeSurface& out);

/// The surface written to the field files: with cells formed again the outline's
/// (outline_free_surface), which the conditions act on; else the detector's.
void field_free_surface(const Simulation& simulation, FreeSurface& out);

/// The nodes on the outline of the body's cells (re-entrant corners excepted, as in the surface the
/// conditions act on). A moving body keeps its cells, so this is its outline at any deformation
/// (§9.1), whatever conditions act on it (a fixed base is on it too: the detector sees only the
/// nodes).
std::vector<std::uint8_t> body_perimeter(const NodeSets& nodes);

/// The detected surface against the body perimeter.
struct SurfaceAgreement {
  std::size_t perimeter_nodes = 0;
  std::size_t missed = 0;          ///< perimeter nodes not detected
  std::size_t false_positive = 0;  ///< detected nodes off the perimeter
  /// (missed + false_positive) / perimeter_nodes
  double misflagged_fraction() const {
    return perimeter_nodes
               ? static_cast<double>(missed + false_positive) / static_cast<double>(perimeter_nodes)
               : 0.0;
  }
};

SurfaceAgreement compare_with_perimeter(const Simulation& simulation, const FreeSurface& detected);

}  // namespace rktsph
