// One Runge-Kutta Taylor-SPH step (docs/theory.md §2.2), written once for every physics model:
//   1   stress points:  Phi^{n+1/2} = I(Phi^n) + RK[frozen R(G(Phi^n))] over dt/2
//   1b  boundary nodes: Phi^{n+1/2} = Phi^n + RK[frozen R(G_SS(Phi^n))] over dt/2, then BCs
//   2   SPH nodes:      Phi^{n+1}   = Phi^n + RK[frozen R(G(Phi^{n+1/2}))] over dt
//   3   boundary conditions at t + dt, hourglass filter (2D), again the conditions, displacement.
// With the mean-velocity stress update (the 2D default, docs/theory.md eq. 2.5) step 2 advances
// the velocity only; every other field is then advanced from Phi^n with the lumped average of the
// stress points' gradients of (v^n + v^{n+1})/2, the velocity of the displacement, and the cells'
// hourglass forces (eq. 3.9) with the same velocity; in V3 after the pressure projection.
// At nodes whose cells are incomplete the momentum balance is the adjoint of the stress points'
// velocity gradient, and the level-n part of the strain rate is the lumped average of theirs
// (docs/theory.md §5.3).
// The operators are weight tables built once (positions are fixed in V1 and V3).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "rktsph/boundary/boundary_conditions.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/physics/physics_model.hpp"
#include "rktsph/physics/state.hpp"
#include "rktsph/sph/adjoint_operator.hpp"
#include "rktsph/sph/operators.hpp"
#include "rktsph/stabilisation/hourglass_stiffness.hpp"
#include "rktsph/stabilisation/strain_hourglass_stiffness.hpp"

namespace rktsph {

struct StepOptions {
  KernelType kernel = KernelType::CubicSpline;
  double h_over_dx = 0.75;
  int interpolation_order = 0;
  bool hourglass_filter = true;  // ignored in 1D, where midpoint stress points have no such mode
  double hourglass_kappa = 0.1;
  double hourglass_h_over_dx = 1.3;
  std::optional<HourglassFields> hourglass_fields;  // unset: Velocity on compact stencils, else All
  StressUpdate stress_update = StressUpdate::HalfStep;
  HourglassStrength hourglass_stiffness;    // epsilon of docs/theory.md eq. 3.3; 0 = off
  double hourglass_plastic_fraction = 0.0;  // psi of eq. 3.9, in flowing cells
  double strain_hourglass_stiffness = 0.0;  // epsilon_s of docs/theory.md eq. 3.5; 0 = off
  double artificial_viscosity = 0.0;        // alpha of prototype R7; 0 = off
};

/// The operator tables of the step and the classification of nodes they imply.
struct StepOperators {
  WeightTable nodes_to_points;    ///< step 1: S -> V interpolation and gradient
  WeightTable points_to_nodes;    ///< step 2: columns [0, nV) stress points, [nV, nV+nS) nodes
  WeightTable boundary_gradient;  ///< step 1b: rows = boundary_nodes, columns = SPH nodes
  std::vector<std::int32_t> boundary_nodes;        ///< nodes with incomplete stencils (step 1b)
  std::vector<std::int32_t> node_to_boundary_row;  ///< -1 for interior nodes
  /// Step 2 closure of every node whose 2^d cells are not all present (the boundary nodes and the
  /// re-entrant corners): the lumped adjoint of nodes_to_points (docs/theory.md eqs. 5.2, 5.3).
  AdjointOperator incomplete_closure;
  bool hourglass_filter = false;
  double hourglass_kappa = 0.0;
  HourglassFields hourglass_fields = HourglassFields::Velocity;
  StressUpdate stress_update = StressUpdate::HalfStep;
  HourglassStrength hourglass_stiffness;    ///< epsilon of the cells' hourglass stiffness (eq. 3.3)
  double hourglass_plastic_fraction = 0.0;  ///< psi of eq. 3.9
  double strain_hourglass_stiffness = 0.0;  ///< epsilon_s of eq. 3.5
  /// Every stress point's stencil is its own cell's corners (h small enough): the lattice
  /// operators then commute in the interior (docs/theory.md §5.3).
  bool compact_stencils = false;
  WeightTable filter_to_points;  ///< first-order round trip of the filter (prototype R6)
  WeightTable filter_to_nodes;
  double viscosity_length = 0.0;  ///< alpha * dx of the artificial viscosity (0 = off)
};

/// The kernel, smoothing length, interpolation order and mirrors of the step's operators.
OperatorOptions step_operator_options(const NodeSets& nodes, const StepOptions& options,
                                      const std::vector<MirrorPlane>& mirrors);

/// Builds the tables; throws RunError naming the node if a stencil cannot be made regular.
StepOperators build_step_operators(const NodeSets& nodes, const StepOptions& options,
                                   const std::vector<MirrorPlane>& mirrors);

/// A correction applied after the RK-TSPH pass and its boundary conditions, before the step ends
/// (the pressure projection of the saturated model, docs/theory.md §6.1). `time` is t^{n+1}.
class StepProjection {
 public:
  virtual ~StepProjection() = default;
  virtual void project(State& state, double time, double dt) = 0;
};

class RkTaylorStep {
 public:
  RkTaylorStep(const PhysicsModel& model, const NodeSets& nodes, StepOperators operators,
               const BoundaryConditions& conditions);

  /// Advances `state` by dt. Allocates nothing.
  void advance(State& state, double dt);

  const StepOperators& operators() const { return operators_; }
  const HourglassStiffness& hourglass_stiffness() const { return hourglass_stiffness_; }
  const StrainHourglassStiffness& strain_hourglass_stiffness() const {
    return strain_hourglass_stiffness_;
  }
  /// Records the imposed stresses of the initial state (after its conditions), the reference of
  /// the strain hourglass stiffness at constrained nodes (docs/theory.md eq. 3.8).
  void set_initial_state(const State& state) {
    strain_hourglass_stiffness_.set_reference(state.fields);
  }
  void set_projection(StepProjection* projection) { projection_ = projection; }
  /// Applies the hourglass filter of step 3 alone (docs/theory.md eq. 3.1); no-op when it is off.
  void filter_hourglass(FieldArray& fields) { filter_hourglass(fields, FilterPart::All); }

 private:
  void step_stress_points(const State& state, double dt);
  void step_boundary_nodes(const State& state, double dt);
  void step_nodes(State& state, double dt);
  void project_free_faces(const FieldArray& start, FieldArray& values, bool boundary_rows) const;
  void close_incomplete_nodes(const State& state);
  void advance_stress_with_mean_velocity(State& state, double dt);
  void finish_with_mean_velocity(State& state, double dt);
  enum class FilterPart { All, Velocity, OtherFields };
  void filter_hourglass(FieldArray& fields, FilterPart part);

  const PhysicsModel& model_;
  const NodeSets& nodes_;
  StepOperators operators_;
  const BoundaryConditions& conditions_;
  StepProjection* projection_ = nullptr;
  HourglassStiffness hourglass_stiffness_;  // docs/theory.md §3.4
  StrainHourglassStiffness strain_hourglass_stiffness_;
  std::vector<std::int32_t> boundary_material_;
  std::vector<Parity> internal_parity_;      // boundary rows whose stress increments are projected
  std::vector<std::uint8_t> momentum_flux_;  // 1 for the fields whose gradient feeds the momentum
  std::vector<std::uint8_t> velocity_gradient_fields_;  // 1 for the gradient fields of v
  std::vector<Parity> gradient_parities_;               // of each gradient field f * d + c
  std::vector<int> filtered_fields_;                    // the fields the hourglass filter acts on
  std::vector<Parity> filtered_parities_;
  std::vector<int> filtered_velocity_fields_, filtered_other_fields_;  // the two parts of it
  std::vector<Parity> filtered_velocity_parities_, filtered_other_parities_;

  // Scratch, allocated once.
  FieldArray half_step_;  // [stress points ; SPH nodes] at t + dt/2
  FieldArray point_gradient_;
  FieldArray point_rate_;
  FieldArray point_internal_;
  FieldArray point_velocity_;  // I(v^n) at the stress points (axis a), before their half step
  FieldArray boundary_values_;
  FieldArray boundary_start_;
  FieldArray boundary_gradient_;
  FieldArray boundary_rate_;
  FieldArray boundary_internal_;
  FieldArray node_gradient_;
  FieldArray node_rate_;
  FieldArray hourglass_force_;               // k q of every cell at t + dt/2 (eq. 3.9)
  std::vector<double> hourglass_factor_;     // 1, or psi in flowing cells
  std::vector<std::uint8_t> point_flowing_;  // of the stress points' half-step state
  std::vector<double> filter_values_;        // node-major copies for the filter's round trip
  std::vector<double> filter_points_;
  std::vector<double> filter_round_trip_;
  std::vector<double> filter_residual_;
  std::vector<double> pore_buffer_;  // p_w kept out of the filter (saturated model)
  // The mean-velocity stress update (eq. 2.5) and the hourglass forces (eq. 3.9).
  AdjointOperator node_average_;  // lumped average over every node
  FieldArray start_fields_;       // Phi^n and kappa^n, to redo the stress update
  FieldArray start_internal_;
  FieldArray mean_velocity_;        // v^n, then (v^n + v^{n+1})/2
  FieldArray mean_point_gradient_;  // G of it at the stress points
  FieldArray mean_node_gradient_;   // its lumped average at the nodes
  std::vector<Parity> velocity_parities_;
  std::vector<Parity> velocity_gradient_parities_;
  std::vector<std::uint8_t> every_gradient_;
};

}  // namespace rktsph
