// How the configuration changes within and between steps (docs/theory.md §2.6, §9.1-§9.7): the
// one RK-TSPH step calls these hooks at fixed places and knows no model by name. A fixed
// configuration (V1, V3) does nothing at any of them; a moving one (V2) turns the stress with the
// spin, weighs the momentum with the current density, maps gradients to the mid-step
// configuration, turns the faces and moves the points after the step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "rktsph/boundary/boundary_conditions.hpp"
#include "rktsph/core/field_array.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/physics/configuration_motion.hpp"
#include "rktsph/physics/physics_model.hpp"
#include "rktsph/physics/state.hpp"
#include "rktsph/time/step_operators.hpp"

namespace rktsph {

class ConfigurationPolicy {
 public:
  virtual ~ConfigurationPolicy() = default;

  /// After a flux rate on `count` rows: the stress of `values` turned with the spin of `gradient`
  /// (dv_a/dx_c at velocity_gradient[a d + c]) over `interval`, the objective rate (eq. 9.2).
  virtual void rotate_stress(const FieldArray& gradient, std::span<const int> velocity_gradient,
                             double interval, std::size_t count, FieldArray& values) const {
    (void)gradient, (void)velocity_gradient, (void)interval, (void)count, (void)values;
  }
  /// The velocity rates of rows [0, count) weighed by V / V_0 of their point (row_point[r], or r):
  /// the momentum balance with the current density rho_0 V_0 / V (eq. 9.3).
  virtual void scale_momentum_rate(FieldArray& rate, std::size_t count,
                                   const double* current_volume, const double* reference_volume,
                                   const std::int32_t* row_point) const {
    (void)rate, (void)count, (void)current_volume, (void)reference_volume, (void)row_point;
  }
  /// Gradients taken on x^n of fields centred at t + dt/2, turned into gradients on the mid-step
  /// configuration x^n + (dt/2) v (eq. 9.5). `gradient` holds `fields` fields of `count` points.
  virtual void to_midpoint_configuration(FieldArray& gradient, int fields,
                                         std::span<const int> velocity_gradient, double dt,
                                         std::size_t count) const {
    (void)gradient, (void)fields, (void)velocity_gradient, (void)dt, (void)count;
  }
  /// The faces turned to the nodes at X + u + (dt/2) v of `state` (§9.7), which are where the
  /// nodes are at `time` (the rigid bodies' contacts are found there, §9.18).
  virtual void turn_faces(const State& state, double dt, double time) {
    (void)state, (void)dt, (void)time;
  }
  /// After the step: the points moved with the displacement (§9.1).
  virtual void after_step(State& state) { (void)state; }
  /// The conditions whose faces turn with the body (the step's own conditions).
  virtual void follow_faces(BoundaryConditions* faces) { (void)faces; }
  /// The motion of the points, or null where they do not move.
  virtual const ConfigurationMotion* motion() const { return nullptr; }
};

/// The configuration of V1 and V3: the reference one, throughout.
class FixedConfiguration final : public ConfigurationPolicy {};

/// The configuration of V2 (docs/theory.md §9): the nodes move with their displacement, the cells
/// follow, and the faces the conditions act on turn with the body.
class MovingConfiguration final : public ConfigurationPolicy {
 public:
  /// `formation`: where and how the cells of `reference` were formed again from the moving nodes
  /// (docs/theory.md §9.17); null for the cells of the start.
  MovingConfiguration(const PhysicsModel& model, const NodeSets& reference,
                      const CellFormation* formation = nullptr);

  void rotate_stress(const FieldArray& gradient, std::span<const int> velocity_gradient,
                     double interval, std::size_t count, FieldArray& values) const override;
  void scale_momentum_rate(FieldArray& rate, std::size_t count, const double* current_volume,
                           const double* reference_volume,
                           const std::int32_t* row_point) const override;
  void to_midpoint_configuration(FieldArray& gradient, int fields,
                                 std::span<const int> velocity_gradient, double dt,
                                 std::size_t count) const override;
  void turn_faces(const State& state, double dt, double time) override;
  void after_step(State& state) override;
  void follow_faces(BoundaryConditions* faces) override { faces_ = faces; }
  const ConfigurationMotion* motion() const override { return &motion_; }

 private:
  const PhysicsModel& model_;
  const NodeSets& reference_;
  const PointCloud& origin_;             // where the displacement is measured from
  BoundaryConditions* faces_ = nullptr;  // the conditions whose faces turn with the body
  ConfigurationMotion motion_;
  PointCloud predicted_nodes_;  // where turn_faces puts the nodes
};

/// The policy that goes with the operators' policy: fixed with ReferenceConfiguration, moving with
/// CurrentConfiguration (`formation` as for MovingConfiguration).
std::unique_ptr<ConfigurationPolicy> make_configuration_policy(
    OperatorPolicy policy, const PhysicsModel& model, const NodeSets& reference,
    const CellFormation* formation = nullptr);

}  // namespace rktsph
