// Zero-energy control (docs/theory.md §3.3-§3.4): what keeps the modes that the step's operators
// do not see (the odd-even pattern of the stress-point cells, the strain modes of nodal stress
// storage, the soft modes of the nodal strain average on triangles) from growing or drifting.
//
// The one RK-TSPH step calls each control at named places and knows none of them by name: a
// control overrides the hooks of the phases it acts in and leaves the others as they are. The
// hooks, in the order of a step (docs/theory.md §2.2):
//   follow_flow            step 1, after the stress points' half step: the cells' flow states,
//                          from which a control that follows viscoplastic flow sets its strength
//                          (eqs. 3.10, 3.14);
//   correct_half_step      step 2, before the nodes' gradient of the half-step values: stress
//                          added at the stress points (the strain stiffness, eqs. 3.6, 3.12);
//   add_node_rate          step 2, the nodes' rates: forces on the nodes (the cells'
//                          Flanagan-Belytschko stiffness, eq. 3.4);
//   record_strain_rate     step 2 or the mean-velocity update: the nodal velocity gradient the
//                          nodal stress is advanced with (the strain that stress received,
//                          eq. 3.5);
//   filter                 step 3, after the conditions of t + dt: a correction of the nodal fields
//                          (the hourglass filter, eq. 3.1), after which the step imposes the
//                          conditions again;
//   finish                 after the step's last update: what the control carries to the next step
//                          advanced with the mean velocity (the cells' forces, eq. 3.9).
// What a control carries from step to step lives in State (State::hourglass_force, State::strain),
// so that checkpoints and restarts hold it; the control only says it needs it.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "rktsph/core/field_array.hpp"
#include "rktsph/mesh/cell_complex.hpp"
#include "rktsph/physics/state.hpp"

namespace rktsph {

/// Which nodal fields a filter pass acts on: the step filters the velocity after the velocity
/// update and the other fields after the mean-velocity update (eq. 2.5), or all at once.
enum class FilteredPart { All, Velocity, OtherFields };

class ZeroEnergyControl {
 public:
  virtual ~ZeroEnergyControl() = default;

  /// The control's name in logs and tests.
  virtual std::string_view name() const = 0;

  // What the control asks of the step and of the state.
  /// The cells' flow states every step (follow_flow).
  virtual bool follows_flow() const { return false; }
  /// The mean velocity (v^n + v^{n+1})/2 at the nodes at finish().
  virtual bool needs_mean_velocity() const { return false; }
  /// State::strain, the strain the nodal stress received (3 fields per node).
  virtual bool carries_received_strain() const { return false; }
  /// State::hourglass_force, one generalised force per cell (2 fields per stress point).
  virtual bool carries_cell_forces() const { return false; }

  /// The initial state, after its conditions (t = 0).
  virtual void start(const State& state) { (void)state; }

  /// `flowing` of every cell (1 flows, 2 has flowed, 0 never; flow_strength.hpp), `scratch` one
  /// entry per node.
  virtual void follow_flow(const CellComplex& cells, std::span<const std::uint8_t> flowing,
                           double plastic_fraction, std::span<std::uint8_t> scratch) {
    (void)cells, (void)flowing, (void)plastic_fraction, (void)scratch;
  }

  /// Adds to the stress points' half-step values (rows [0, nV) of `half_step`). `state` holds
  /// u^{n+1/2}; `point_gradient` is the stress points' gradient of Phi^n.
  virtual void correct_half_step(const State& state, const FieldArray& point_gradient, double dt,
                                 FieldArray& half_step) {
    (void)state, (void)point_gradient, (void)dt, (void)half_step;
  }

  /// Adds to the nodes' rates of step 2; `state` holds Phi^n (and u^{n+1/2}).
  virtual void add_node_rate(const State& state, double dt, FieldArray& rate) {
    (void)state, (void)dt, (void)rate;
  }

  /// The model's nodal gradient with the velocity gradient the nodal stress is advanced with.
  virtual void record_strain_rate(const FieldArray& node_gradient, double dt, State& state) {
    (void)node_gradient, (void)dt, (void)state;
  }

  /// Corrects `part` of the nodal `fields` after the conditions of t + dt; true if it changed
  /// anything (the step then imposes the conditions again).
  virtual bool filter(FilteredPart part, FieldArray& fields) {
    (void)part, (void)fields;
    return false;
  }

  /// After the step's last update: `mean_velocity` is (v^n + v^{n+1})/2 at the nodes (d fields),
  /// `mean_point_gradient` its gradient at the stress points, empty without the mean-velocity
  /// update.
  virtual void finish(const FieldArray& mean_velocity, const FieldArray& mean_point_gradient,
                      double dt, State& state) {
    (void)mean_velocity, (void)mean_point_gradient, (void)dt, (void)state;
  }
};

}  // namespace rktsph
