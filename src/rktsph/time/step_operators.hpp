// The operator tables of the RK-TSPH step and the one builder that makes them from a
// configuration (docs/theory.md §2.6): classification of the nodes, the step's tables, the
// hourglass filter's tables. A model's policy says when they are built: once on the reference
// configuration (V1, V3, whose points do not move), or on the current configuration before every
// step (a large-deformation model).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "rktsph/core/step_choices.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/physics/state.hpp"
#include "rktsph/sph/adjoint_operator.hpp"
#include "rktsph/sph/neighbour_search.hpp"
#include "rktsph/sph/operators.hpp"
#include "rktsph/stabilisation/hourglass_stiffness.hpp"
#include "rktsph/stabilisation/strain_hourglass_stiffness.hpp"

namespace rktsph {

/// The step's settings, resolved from the case's numerics once (the one copy the step reads).
struct StepOptions {
  KernelType kernel = KernelType::CubicSpline;
  double h_over_dx = 0.75;
  int interpolation_order = 0;
  bool hourglass_filter = true;  // ignored in 1D, where midpoint stress points have no such mode
  double hourglass_kappa = 0.1;
  double hourglass_h_over_dx = 1.3;
  /// On a moving configuration the stencils are searched again and the filter's tables rebuilt
  /// once a node has moved this fraction of dx since the last search (docs/theory.md §9.5); 0:
  /// before every step. The weights follow the nodes every step.
  double neighbour_search_distance = 0.1;
  std::optional<HourglassFields> hourglass_fields;  // unset: Velocity on compact stencils, else All
  StressUpdate stress_update = StressUpdate::HalfStep;
  HourglassStrength hourglass_stiffness;    // epsilon of docs/theory.md eq. 3.3; 0 = off
  double hourglass_plastic_fraction = 0.0;  // psi of eq. 3.9, in flowing cells
  double strain_hourglass_stiffness = 0.0;  // epsilon_s of eq. 3.5 or beta of eq. 3.12; 0 = off
  StrainControl strain_control = StrainControl::Received;  // which of the two (theory §3.4)
  double artificial_viscosity = 0.0;                       // alpha of docs/theory.md §2.7; 0 = off
};

/// When the operators are built (docs/theory.md §2.6).
enum class OperatorPolicy {
  ReferenceConfiguration,  ///< once, before the first step: the points do not move (V1, V3)
  CurrentConfiguration,    ///< before every step, on the configuration of the state
};

/// The tables of the step and the classification of nodes they imply. Tables only: the settings
/// stay in StepOptions.
struct StepOperators {
  WeightTable nodes_to_points;    ///< step 1: S -> V interpolation and gradient
  WeightTable points_to_nodes;    ///< step 2: columns [0, nV) stress points, [nV, nV+nS) nodes
  WeightTable boundary_gradient;  ///< step 1b: rows = boundary_nodes, columns = SPH nodes
  std::vector<std::int32_t> boundary_nodes;        ///< nodes with incomplete stencils (step 1b)
  std::vector<std::int32_t> node_to_boundary_row;  ///< -1 for interior nodes
  /// Nodes whose 2^d cells are not all present (the boundary nodes and the re-entrant corners).
  std::vector<std::int32_t> incomplete_nodes;
  /// Their step 2 closure: the lumped adjoint of nodes_to_points (docs/theory.md eqs. 5.2, 5.3).
  AdjointOperator incomplete_closure;
  /// Every stress point's stencil is its own cell's corners (h small enough): the lattice
  /// operators then commute in the interior (docs/theory.md §5.3).
  bool compact_stencils = false;
  /// Rows whose correction matrix was singular and that took the uncorrected SPH gradient
  /// instead (docs/theory.md §9.5): only on a moving configuration; a build on the initial
  /// configuration throws instead.
  std::size_t fallback_rows = 0;
  WeightTable filter_to_points;  ///< first-order round trip of the filter (docs/theory.md §3.3)
  WeightTable filter_to_nodes;
};

/// Builds StepOperators from a configuration, reusing its own buffers and the tables' arrays.
class StepOperatorBuilder {
 public:
  /// `reference` gives the cells (which nodes are the corners of which stress point) and the
  /// materials; `mirror_axes[n]` has bit a set when node n lies on a mirror plane normal to a.
  StepOperatorBuilder(const NodeSets& reference, const StepOptions& options,
                      std::vector<MirrorPlane> mirrors, std::span<const std::uint8_t> mirror_axes);

  /// Everything: classify, then the step's tables, then the filter's. Throws RunError naming the
  /// point if a stencil cannot be made regular.
  void build(const Configuration& configuration, StepOperators& operators);
  /// Boundary nodes and incomplete nodes from the node topology (docs/theory.md §2.6).
  void classify(const Configuration& configuration, StepOperators& operators);
  /// nodes_to_points, points_to_nodes, boundary_gradient, the incomplete nodes' closure. With
  /// keep_stencil_candidates the stencils are searched in the cell lists only when `search`.
  void build_step_tables(const Configuration& configuration, StepOperators& operators,
                         bool search = true);
  /// The hourglass filter's round trip (no-op when the filter is off).
  void build_filter_tables(const Configuration& configuration, StepOperators& operators);

  /// The kernel, smoothing length, interpolation order and mirrors of the step's operators.
  const OperatorOptions& operator_options() const { return operator_options_; }
  /// True when the filter acts (2D and up, on, kappa > 0).
  bool filter_active() const;
  /// From now on a row whose stencil cannot be made regular takes the uncorrected gradient and is
  /// counted in StepOperators::fallback_rows, instead of stopping the run (moving configurations).
  void fall_back_on_degenerate_stencils() { fall_back_ = true; }
  /// From now on the rows of the step's and the filter's tables keep their own weights instead of
  /// sharing them by stencil (docs/theory.md §4.7): on a moving configuration no two rows are
  /// alike, so the sharing pass would cost a quarter of the rebuild and save nothing (§9.5).
  void keep_weights_per_row() { share_weights_ = false; }
  /// From now on the step's stencils come from a neighbour list with a skin (docs/theory.md §9.5):
  /// every source within the support plus 2 `search_distance` [m] of each row's target, searched
  /// in the cell lists when build_step_tables is asked to search; the builds in between pick each
  /// row's stencil from them at the current positions, which is exact while no point has moved
  /// more than `search_distance` since the search (no pair has then come closer by more than
  /// twice that). A distance of 0 keeps a search in every build.
  void keep_stencil_candidates(double search_distance) { candidate_skin_ = 2.0 * search_distance; }
  /// Frees the buffers kept for the next build (the row blocks, the sharing workspace, the cell
  /// lists and candidate lists) and the capacity of the tables of `operators` beyond their sizes:
  /// a fixed configuration builds once (docs/theory.md §4.7). A later build grows them again.
  void release_buffers(StepOperators& operators);
  /// The wall time every build so far spent on the neighbour search's cell lists [s].
  double cell_list_seconds() const { return cell_list_seconds_; }

 private:
  const NodeSets& reference_;
  StepOptions options_;
  OperatorOptions operator_options_;
  OperatorOptions filter_options_;       // the hourglass filter's round trip
  OperatorOptions cell_corner_options_;  // stress points on cell stencils: first order (§4.8)
  std::vector<std::uint8_t> mirror_axes_;
  // The classification depends only on the lattice topology and the mirror axes: made once and
  // copied into later builds' operators (a moving configuration keeps its topology, §9.1).
  bool classified_ = false;
  bool fall_back_ = false;
  bool cell_stencils_ = false;  // stencils from the complex, not a radius (§4.8)
  bool simplices_ = false;      // every cell a simplex: no hourglass mode to filter (§3.3)
  bool share_weights_ = true;
  double candidate_skin_ = 0.0;  // [m]; 0: every build searches the cell lists at the support
  struct CandidateTable {
    std::vector<std::int64_t> start;  // row r: entries[start[r], start[r + 1])
    std::vector<StencilCandidate> entries;
  };
  CandidateTable point_row_candidates_, node_row_candidates_, boundary_row_candidates_;
  std::vector<std::vector<StencilCandidate>> candidate_scratch_;  // per row, during a search
  double cell_list_seconds_ = 0.0;
  /// The candidates of the three kinds of rows: nodes_to_points (point rows, node sources),
  /// points_to_nodes (node rows, point sources), the boundary nodes' collocated rows (node
  /// sources, the node itself left out; also the boundary neighbours of a corner's retry).
  void search_candidates(const PointCloud& nodes, const PointCloud& points,
                         const std::vector<std::int32_t>& boundary_nodes, double radius);
  /// A node's row of points_to_nodes from the cells (docs/theory.md §4.8).
  RowTarget cell_node_row(const Configuration& configuration, std::size_t node,
                          std::int32_t n_points, std::span<const std::int32_t> boundary_row,
                          std::vector<StencilSource>& stencil);
  /// How near a mirror plane a node lies on it, as the radius search tests it [m].
  double plane_tolerance() const { return 1e-8 * operator_options_.smoothing_length; }
  /// Counts `rows` degenerate rows, or throws `message` for the first when not falling back.
  void degenerate(std::size_t rows, StepOperators& operators, const std::string& message) const;
  std::vector<std::int32_t> boundary_nodes_, node_to_boundary_row_, incomplete_nodes_;
  // The tables' buffers, kept between builds so that a rebuild allocates nothing once grown.
  OperatorWorkspace workspace_;
  std::vector<std::vector<StencilSource>> retry_stencils_;  // boundary neighbours of a corner
  ShareWorkspace share_workspace_;
  std::vector<std::int32_t> own_column_;
  CellList node_cells_, point_cells_;  // rebuilt in place (no allocation once grown)
};

}  // namespace rktsph
