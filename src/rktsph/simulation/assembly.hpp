// A run assembled from its case (docs/theory.md §2.6): the reference configuration and groups, the
// materials and the physics model from the model registry, the boundary conditions, the time step,
// the step with its operators, the model's projection and the initial state. Everything is checked
// before it is built. The time loop (simulation.hpp) runs what this assembles.
#pragma once

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rktsph/boundary/boundary_conditions.hpp"
#include "rktsph/case/case_description.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/models/model_registry.hpp"
#include "rktsph/models/pressure_projection.hpp"
#include "rktsph/physics/physics_model.hpp"
#include "rktsph/physics/state.hpp"
#include "rktsph/time/rk_taylor_step.hpp"

namespace rktsph {

/// What a run may ask for; checked from the case before anything is built.
struct SimulationLimits {
  /// Largest estimated number of SPH nodes (the `--max-nodes` flag of run and check).
  double max_nodes = 1e7;
};

/// Resident memory of a run [bytes] of `model` with this many SPH nodes, lattice points of the
/// node lookup and smoothing length h/dx: measured peak RSS per node (/usr/bin/time -v, runs of
/// 1.5e5-1.6e5 nodes, docs/input-reference.md "Limits"): at h = 0.75 dx 1.26 KB for the dry model,
/// 2.6 KB saturated, 3.7 KB on a moving configuration; at 1.3 dx 4.2, 5.0 and 6.0 KB. Rounded up,
/// plus 6 KB per unit of h/dx above 0.75 (an upper bound of the three slopes) and 4 bytes per
/// lattice point.
double estimated_run_memory(ModelKind model, double sph_nodes, double lattice_points,
                            double h_over_dx);

/// The largest Courant number at which the step is stable, measured as the spectral radius of the
/// full step matrix (<= 1 + 1e-9) on a 12 x 5 block with every boundary type (docs/theory.md
/// §2.5, tests CourantLimit*): on compact stencils the Lax-Wendroff limit 1 lowered by the
/// artificial viscosity alpha to sqrt(1 + alpha^2) - alpha (measured 1.013, 0.791, 0.643, 0.433
/// at alpha = 0, 0.25, 0.5, 1; the formula gives 1, 0.781, 0.618, 0.414); 2D stencils wider than
/// a cell are stable only up to 0.766 at h = 1.3 dx without viscosity, so they are held to 0.75.
double stable_courant_limit(double viscosity, bool compact_stencils);

/// The first clamped-free bending mode of a beam of length L at distance xi from its root,
/// normalised to 1 at the tip: [cosh k xi - cos k xi] - s [sinh k xi - sin k xi] with
/// k L = 1.875104 and s = (cosh kL + cos kL)/(sinh kL + sin kL); xi is clamped to [0, L] (the
/// initial_conditions.bending_mode of docs/input-reference.md).
double bending_mode_shape(double xi, double length);

/// What forming the cells again has done over a run (docs/theory.md §9.17): how many times, the
/// cells formed in all and the Delaunay triangles the alpha criterion dropped in all, the cells
/// now, and the wall time it took.
struct CellForming {
  long formings = 0;
  long cells_formed = 0;
  long triangles_dropped = 0;
  long triangles_restored = 0;  ///< dropped ones kept again to join fans (§3.9)
  std::size_t cells_now = 0;
  std::size_t isolated_nodes = 0;  ///< in no cell at the last forming
  /// The narrowest formed cell's width over the one that set dt (below 1: a forming made the
  /// step's Courant number larger than the case's, §9.17).
  double narrowest_cell_ratio = 1.0;
  double seconds = 0.0;
  /// The step's time split of the steps before the last forming (a new step starts its own).
  StepTimeSplit earlier_steps;
  long earlier_neighbour_searches = 0;
  /// Steps taken in parts, and the most parts of one step (step_parts()).
  long divided_steps = 0;
  int most_parts = 1;
  long nodes_spread = 0;  ///< crowded nodes moved before a forming (eq. 9.16)
};

class Assembly {
 public:
  /// Builds everything; InputError for inconsistent input or a case above `limits`, RunError for
  /// an unusable lattice.
  explicit Assembly(CaseDescription description, SimulationLimits limits = {});
  Assembly(const Assembly&) = delete;
  Assembly& operator=(const Assembly&) = delete;

  const CaseDescription& description() const { return description_; }
  /// The reference configuration: stable ids, materials, the cells of the start.
  const NodeSets& nodes() const { return nodes_; }
  /// The cells the step integrates over now: those of the start, or those formed again from the
  /// moving nodes (numerics.cells.policy: reformed), held at their positions of forming.
  const NodeSets& cells() const { return formed_ ? *formed_ : nodes_; }
  /// True when the case forms its cells again from the moving nodes (docs/theory.md §9.17).
  bool forms_cells() const;
  /// True when a cell has distorted past numerics.cells.reform_below since it was formed.
  bool cells_need_forming() const;
  /// Forms the cells again from the nodes where they are, and the conditions and the step on
  /// them; the state (on the nodes) is kept. RunError where no valid cells can be formed.
  void form_cells();
  const CellForming& cell_forming() const { return forming_; }
  /// Where the cells were last formed, and the forming counts: a restart forms the same cells.
  void save_cell_forming(CheckpointOut& out) const;
  /// Reads what save_cell_forming wrote and forms the cells there (before the configuration is
  /// restored); CheckpointIn::fail where the checkpoint and the case disagree.
  void restore_cell_forming(CheckpointIn& in);
  /// How many equal parts the next step is taken in: 1, or with formed cells narrower than the
  /// width that set dt, enough that none of them sees a larger Courant number than the case's
  /// (docs/theory.md §2.5, §9.17).
  int step_parts() const;
  void count_divided_step(int parts) {
    ++forming_.divided_steps;
    forming_.most_parts = std::max(forming_.most_parts, parts);
  }
  const std::map<std::string, std::vector<std::int32_t>>& groups() const { return groups_; }
  const PhysicsModel& model() const { return *model_; }
  const RegisteredModel& registered_model() const { return *registered_; }
  const BoundaryConditions& boundary_conditions() const { return *conditions_; }
  /// Around each step (or part of one) of `length`: the loaded rigid bodies' own motion over it
  /// (docs/theory.md eq. 9.17), under the case's gravity at mid-step.
  void begin_body_step(double length);
  void end_body_step() { conditions_->end_body_step(); }
  /// The rigid bodies' motions, for a restart (before the configuration follows the state).
  void save_bodies(CheckpointOut& out) const { conditions_->save_bodies(out); }
  void restore_bodies(CheckpointIn& in) { conditions_->restore_bodies(in); }
  const RkTaylorStep& step() const { return *step_; }
  RkTaylorStep& step() { return *step_; }
  const State& state() const { return state_; }
  State& state() { return state_; }
  double time_step() const { return time_step_; }
  /// The model's correction after the RK-TSPH pass (the pressure projection of V3), or null.
  StepProjection* projection() const { return projection_.get(); }
  long total_steps() const { return total_steps_; }
  /// The size estimated from the shapes before the lattice was built.
  const NodeEstimate& node_estimate() const { return node_estimate_; }
  /// estimated_run_memory() of the lattice that was built [bytes].
  double estimated_memory() const;

 private:
  void initialise_state();
  /// The step's options on formed cells (triangles): their zero-energy control (§9.17).
  StepOptions formed_cell_options() const;
  /// Forms the cells from the nodes at `formation` (positions and volumes) and builds the
  /// conditions and the step on them, its controls started from `fields`; the configuration's
  /// nodes are set to `formation`.
  void form_cells_at(const PointCloud& formation, const FieldArray& fields);
  /// Each node's spacing at `nodes` (positions and volumes now), for eqs. 3.15 and 9.16.
  std::vector<double> node_spacing_at(const PointCloud& nodes) const;
  /// The rigid bodies' outlines now: no formed cell crosses them, no spread node enters them.
  std::vector<std::vector<Vec3>> rigid_bodies_now() const;
  /// numerics.cells.spread_below: crowded nodes moved before a forming (eq. 9.16).
  void spread_crowded_nodes_before_forming();
  /// initial_conditions.stress, on top of the geostatic stress.
  void add_initial_stress();
  /// initial_conditions.angular_velocity and bending_mode, on top of the uniform velocity.
  void add_initial_motion();
  /// Where dt comes from, with the values, for messages.
  std::string time_step_origin(const std::vector<std::string>& material_names) const;

  CaseDescription description_;
  NodeSets nodes_;
  std::unique_ptr<NodeSets> formed_;      // the cells formed again, or null (§9.17)
  std::vector<double> node_spacing_;      // each node's spacing at the start, for eq. 3.15
  std::vector<double> formation_volume_;  // the nodes' volumes when the cells were last formed
  FieldArray formation_fields_;           // the fields then: the controls' start (eq. 3.8)
  StepOptions step_options_;
  CellForming forming_;
  std::map<std::string, std::vector<std::int32_t>> groups_;
  const RegisteredModel* registered_ = nullptr;
  std::unique_ptr<PhysicsModel> model_;
  std::unique_ptr<BoundaryConditions> conditions_;
  std::unique_ptr<RkTaylorStep> step_;
  std::unique_ptr<StepProjection> projection_;
  State state_;
  NodeEstimate node_estimate_;
  double time_step_ = 0.0;
  double courant_length_ = 0.0;  ///< [m] dx on a lattice, else the smallest cell width (§2.5)
  long total_steps_ = 0;
};

}  // namespace rktsph
