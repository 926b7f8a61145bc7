// How a large-deformation model moves its configuration (docs/theory.md §9.1): the SPH nodes with
// their displacement, the stress points as the centroids of their cells' corner nodes, and the
// volumes from the cells' current areas. The fields live on the SPH nodes, so a stress point
// carries no state to remap: its position and volume follow from the nodes, and mass (rho_0 V_0
// per point) is conserved exactly.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
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
  /// Smallest ratio of a corner's Jacobian to the one it had when its cell was formed (1D: of a
  /// cell's length): what sets off forming the cells again (docs/theory.md §9.17).
  double smallest_corner_ratio = 1.0;
  /// Largest such ratio: a cell stretched so far that its corners leave the support its stencil
  /// was given when it was formed (§9.17).
  double largest_corner_ratio = 1.0;
  /// Formed cells: the largest ratio of a cell's squared reach (centroid to farthest corner) to its
  /// value at forming. A cell drawn out at constant area keeps its corner Jacobians and still
  /// leaves the support its stencil was given (§4.8, §9.17).
  double largest_reach_ratio = 1.0;
  /// The narrowest cell's width now [m] (formed cells only, else 0): where it is below the width
  /// that set dt, the loop divides the step (docs/theory.md §2.5, §9.17).
  double narrowest_width = 0.0;
};

inline constexpr double kDistortedCornerRatio = 0.2;

/// Cells formed again from the moving nodes (docs/theory.md §9.17): the positions the
/// displacement is measured from (the start's) and each node's volume when they were formed.
struct CellFormation {
  const PointCloud* origin = nullptr;
  std::span<const double> node_volume;  ///< held by whoever formed the cells, for the motion's life
};

class ConfigurationMotion {
 public:
  /// Moves the cells of `reference` (its cell complex). Cells formed again from the moving nodes
  /// (`formation`, docs/theory.md §9.17) are held in `reference` at their positions of forming;
  /// the displacement is then measured from the formation's origin, and the volumes of the nodes
  /// grow from theirs at forming (eq. 9.11).
  explicit ConfigurationMotion(const NodeSets& reference, const CellFormation* formation = nullptr);

  /// Places node i at X_i + u_i and each stress point at the mean of its corners; sets each
  /// cell's volume to its reference volume times its area ratio, and each node's to its reference
  /// volume times the area ratio of the cells around it (formed cells: each cell's to its area,
  /// each node's to its volume at forming times that ratio, eq. 9.11). Reports the cells' quality.
  void move(const FieldArray& displacement, Configuration& configuration);

  /// True for cells formed again from the moving nodes (§9.17).
  bool formed() const { return formed_; }
  /// The cells' quality after the last move.
  const CellQuality& quality() const { return quality_; }
  /// V / V_0 of each SPH node after the last move (1 before the first).
  const std::vector<double>& node_volume_ratio() const { return node_volume_ratio_; }

 private:
  const NodeSets& reference_;  // its cells: corners, cells at each node, reference measures
  const PointCloud& origin_;   // where the displacement is measured from
  bool formed_;                // cells formed again (§9.17)
  std::span<const double> base_node_volume_;  // the reference's volumes, or the formation's
  std::vector<double> reference_reach_;       // formed cells: each cell's squared reach at forming
  std::vector<std::array<double, kMaxCellCorners>> reference_corner_jacobian_;
  std::vector<double> cell_area_;                 // current measure of each cell [m^d]
  std::vector<double> reference_node_cell_area_;  // sum of the reference areas of node n's cells
  std::vector<double> node_volume_ratio_;
  CellQuality quality_;
};

}  // namespace rktsph
