// How a large-deformation model moves its configuration (docs/theory.md §9.1): the SPH nodes with
// their displacement, the stress points as the centroids of their cells' corner nodes, and the
// volumes from the cells' current areas. The fields live on the SPH nodes, so a stress point
// carries no state to remap: its position and volume follow from the nodes, and mass (rho_0 V_0
// per point) is conserved exactly.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rktsph/core/field_array.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/physics/configuration.hpp"

namespace rktsph {

/// The state of the cells after a move (docs/theory.md §9.1).
struct CellQuality {
  /// Smallest ratio of a cell's current to its reference volume (its mean Jacobian), and the
  /// cell it belongs to.
  double smallest_volume_ratio = 1.0;
  std::int32_t smallest_cell = -1;
  /// Cells with a corner whose Jacobian (the cross product of its two edges, over the reference
  /// one) is below kDistortedCornerRatio: distorted enough that their stress point is a poor
  /// centre of their nodes.
  std::size_t distorted_cells = 0;
  /// Cells with a non-positive corner Jacobian and a positive area: concave (an arrowhead), their
  /// nodes still in order around a positive area, so they keep integrating (§9.1).
  std::size_t concave_cells = 0;
  /// Cells whose area is zero or negative: inverted, nodes crossed (the run stops, §9.1).
  std::size_t inverted_cells = 0;
  std::int32_t first_inverted_cell = -1;
};

inline constexpr double kDistortedCornerRatio = 0.2;

class ConfigurationMotion {
 public:
  /// Moves the cells of `reference` (its cell complex).
  explicit ConfigurationMotion(const NodeSets& reference);

  /// Places node i at X_i + u_i and each stress point at the mean of its corners; sets each
  /// cell's volume to its reference volume times its area ratio, and each node's to its reference
  /// volume times the area ratio of the cells around it. Reports the cells' quality.
  void move(const FieldArray& displacement, Configuration& configuration);

  /// The cells' quality after the last move.
  const CellQuality& quality() const { return quality_; }
  /// V / V_0 of each SPH node after the last move (1 before the first).
  const std::vector<double>& node_volume_ratio() const { return node_volume_ratio_; }

 private:
  const NodeSets& reference_;  // its cells: corners, cells at each node, reference measures
  std::vector<std::array<double, kMaxCellCorners>> reference_corner_jacobian_;
  std::vector<double> cell_area_;                 // current measure of each cell [m^d]
  std::vector<double> reference_node_cell_area_;  // sum of the reference areas of node n's cells
  std::vector<double> node_volume_ratio_;
  CellQuality quality_;
};

}  // namespace rktsph
