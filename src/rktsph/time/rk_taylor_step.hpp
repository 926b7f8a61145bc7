// One Runge-Kutta Taylor-SPH step (docs/theory.md §2.2), written once for every physics model:
//   1   stress points:  Phi^{n+1/2} = I(Phi^n) + RK[frozen R(G(Phi^n))] over dt/2
//   1b  boundary nodes: Phi^{n+1/2} = Phi^n + RK[frozen R(G_SS(Phi^n))] over dt/2, then BCs
//   2   SPH nodes:      Phi^{n+1}   = Phi^n + RK[frozen R(G(Phi^{n+1/2}))] over dt
//   3   boundary conditions at t + dt, hourglass filter (2D), again the conditions, displacement.
// With the mean-velocity stress update (the 2D default, docs/theory.md eq. 2.5) step 2 advances
// the velocity only; every other field is then advanced from Phi^n with the lumped average of the
// stress points' gradients of (v^n + v^{n+1})/2, the velocity of the displacement, and the cells'
// hourglass forces (eq. 3.9) with the same velocity; in V3 after the pressure projection.
// The zero-energy controls (stabilisation/zero_energy_control.hpp) act at the step's named hooks;
// the step knows none of them by name.
// At nodes whose cells are incomplete the momentum balance is the adjoint of the stress points'
// velocity gradient, and the level-n part of the strain rate is the lumped average of theirs
// (docs/theory.md §5.3).
// The operators are weight tables from the one builder (time/step_operators.hpp), built once on the
// reference configuration or before every step on the current one (the model's policy,
// docs/theory.md §2.6).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "rktsph/boundary/boundary_conditions.hpp"
#include "rktsph/core/checkpoint.hpp"
#include "rktsph/core/step_time_split.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/physics/configuration_motion.hpp"
#include "rktsph/physics/physics_model.hpp"
#include "rktsph/physics/state.hpp"
#include "rktsph/sph/adjoint_operator.hpp"
#include "rktsph/sph/operators.hpp"
#include "rktsph/stabilisation/zero_energy_control.hpp"
#include "rktsph/time/configuration_policy.hpp"
#include "rktsph/time/step_operators.hpp"
#include "rktsph/time/zero_energy_controls.hpp"

namespace rktsph {

/// A correction applied after the RK-TSPH pass and its boundary conditions, before the step ends
/// (the pressure projection of the saturated model, docs/theory.md §6.2). `time` is t^{n+1}.
class StepProjection {
 public:
  virtual ~StepProjection() = default;
  virtual void project(State& state, double time, double dt) = 0;
  /// What the next step depends on beyond the state (a solver's warm start); nothing by default.
  virtual void save_checkpoint(CheckpointOut& out) const { (void)out; }
  virtual void restore_checkpoint(CheckpointIn& in) { (void)in; }
};

class RkTaylorStep {
 public:
  /// Builds the operators on `configuration` (the initial one) with `builder`; with the policy
  /// CurrentConfiguration they are rebuilt on the state's configuration before every step. With
  /// cells formed again from the moving nodes, `reference` holds them at their positions of
  /// forming and `formation` says where the displacement is measured from (docs/theory.md §9.17).
  RkTaylorStep(const PhysicsModel& model, const NodeSets& reference, const StepOptions& options,
               StepOperatorBuilder builder, OperatorPolicy policy,
               const BoundaryConditions& conditions, const Configuration& configuration,
               const CellFormation* formation = nullptr);

  /// Advances `state` by dt. Allocates nothing with the policy ReferenceConfiguration.
  void advance(State& state, double dt);

  const StepOperators& operators() const { return operators_; }
  const StepOptions& options() const { return options_; }
  const OperatorOptions& operator_options() const { return builder_.operator_options(); }
  /// Rebuilds the operators on `configuration` and what the step derives from them: all of them on
  /// a fixed configuration; on a moving one the step's weights, and its stencils and the filter's
  /// tables once a node has moved the search distance since the last search (docs/theory.md §9.5).
  void rebuild_operators(const Configuration& configuration);
  /// The zero-energy controls that act, in the order the step calls them.
  const ZeroEnergyControls& controls() const { return controls_; }
  /// The control of type Control, or null if none of that type acts.
  template <class Control>
  Control* control() const {
    for (const auto& control : controls_)
      if (auto* found = dynamic_cast<Control*>(control.get())) return found;
    return nullptr;
  }
  /// Whether a control carries the strain the nodal stress received (State::strain) or the cells'
  /// generalised forces (State::hourglass_force) from step to step.
  bool carries_received_strain() const;
  bool carries_cell_forces() const;
  /// The initial state after its conditions, handed to the controls (the strain stiffness keeps
  /// its imposed stresses as the reference of eq. 3.8).
  void set_initial_state(const State& state) {
    for (const auto& control : controls_)
      control->start(state);
  }
  void set_projection(StepProjection* projection) { projection_ = projection; }
  /// The conditions whose faces follow the moving configuration (policy CurrentConfiguration):
  /// the same object as the step's conditions, which it turns after every move.
  void set_moving_surface(BoundaryConditions* conditions) {
    configuration_->follow_faces(conditions);
  }
  /// Where the wall time of every advance so far went (docs/theory.md §9.5).
  StepTimeSplit time_split() const;
  /// How many times the stencils were searched and the filter's tables built on a moving
  /// configuration (docs/theory.md §9.5), the search at the start included.
  long neighbour_searches() const { return neighbour_searches_; }
  /// The configuration of the last search and the count of searches (moving configurations;
  /// nothing otherwise): a restart searches again from it and gets the same stencils and filter.
  void save_checkpoint(CheckpointOut& out) const;
  void restore_checkpoint(CheckpointIn& in);
  /// The moving configuration and its faces placed from the state's displacement, as after a
  /// step: after a restore, so that the cells' quality, which decides when they are formed again
  /// and in how many parts a step is taken (docs/theory.md §9.17), is the run's; and after a
  /// forming, so that a run restarted there continues as it does.
  void follow_state(State& state) { configuration_->after_step(state); }
  /// The motion of the configuration (policy CurrentConfiguration), or null.
  const ConfigurationMotion* motion() const { return configuration_->motion(); }

 private:
  void bind_operators(const Configuration& configuration);
  /// True when a node has moved neighbour_search_distance dx since the last search.
  bool neighbours_out_of_date(const Configuration& configuration) const;
  /// Searches the stencils, builds the step's tables and the filter's on `configuration`, and
  /// keeps it as the configuration of the last search.
  void search_neighbours(const Configuration& configuration);
  /// u += dt/2 v, one half of the trapezoidal displacement update.
  void add_half_step_displacement(State& state, double dt) const;
  void step_stress_points(const State& state, double dt);
  // The cells' flow states, handed to the controls that follow flow (eqs. 3.10, 3.14).
  void update_flow_strengths(const State& state);
  // The controls' filters on `part` of the fields, then the conditions of `time` again if one
  // changed them.
  void filter_fields(FilteredPart part, double time, FieldArray& fields);
  void step_boundary_nodes(const State& state, double dt);
  void step_nodes(State& state, double dt);
  void project_free_faces(const FieldArray& start, FieldArray& values, bool boundary_rows) const;
  void close_incomplete_nodes(const State& state);
  void advance_stress_with_mean_velocity(State& state, double dt);
  void finish_with_mean_velocity(State& state, double dt);

  const PhysicsModel& model_;
  const NodeSets& nodes_;  // the reference configuration: materials, cells
  StepOptions options_;
  StepOperatorBuilder builder_;
  OperatorPolicy policy_;
  StepOperators operators_;
  std::unique_ptr<ConfigurationPolicy> configuration_;  // how the points move, if they do
  // The time split (docs/theory.md §9.5): every advance, its rebuilds, the rebuilds' cell lists,
  // its moves [s].
  double advance_seconds_ = 0.0;
  double rebuild_seconds_ = 0.0;
  double cell_list_seconds_ = 0.0;
  double surface_seconds_ = 0.0;
  // Where dv_a/dx_c sits (a * d + c): in a gradient of every field, in one of the velocity only.
  std::vector<int> velocity_gradient_of_fields_, velocity_gradient_of_velocity_;
  // Moving configurations: where the stencils were last searched and the filter built, and the
  // count of searches (docs/theory.md §9.5).
  Configuration search_configuration_;
  long neighbour_searches_ = 0;
  double viscosity_length_ = 0.0;  // alpha * dx of the artificial viscosity (0 = off)
  const BoundaryConditions& conditions_;
  StepProjection* projection_ = nullptr;
  ZeroEnergyControls controls_;  // docs/theory.md §3.3-§3.4
  std::vector<std::int32_t> boundary_material_;
  std::vector<Parity> internal_parity_;      // boundary rows whose stress increments are projected
  std::vector<std::uint8_t> momentum_flux_;  // 1 for the fields whose gradient feeds the momentum
  std::vector<std::uint8_t> velocity_gradient_fields_;  // 1 for the gradient fields of v
  std::vector<Parity> gradient_parities_;               // of each gradient field f * d + c

  // Scratch, allocated once.
  FieldArray half_step_;  // [stress points ; SPH nodes] at t + dt/2
  FieldArray point_gradient_;
  FieldArray rate_;  // the stress points' rates in step 1, then the nodes' in step 2
  FieldArray point_internal_;
  FieldArray point_velocity_;  // I(v^n) at the stress points (axis a), before their half step
  FieldArray boundary_values_;
  FieldArray boundary_start_;
  FieldArray boundary_gradient_;
  FieldArray boundary_rate_;
  FieldArray boundary_internal_;
  FieldArray node_gradient_;
  std::vector<std::uint8_t> point_flowing_;   // cells: 1 flows, 2 has flowed, 0 never (3.10)
  std::vector<std::uint8_t> node_near_flow_;  // nodes: flowed, then scratch of the factors
  // The mean-velocity stress update (eq. 2.5) and the hourglass forces (eq. 3.9).
  AdjointOperator node_average_;  // lumped average over every node
  std::vector<std::int32_t> every_node_, no_own_value_;
  FieldArray start_fields_;  // Phi^n and kappa^n, to redo the stress update
  FieldArray start_internal_;
  FieldArray mean_velocity_;        // v^n, then (v^n + v^{n+1})/2
  FieldArray mean_point_gradient_;  // G of it at the stress points
  FieldArray mean_node_gradient_;   // its lumped average at the nodes
  std::vector<Parity> velocity_parities_;
  std::vector<Parity> velocity_gradient_parities_;
  std::vector<std::uint8_t> every_gradient_;
};

}  // namespace rktsph
