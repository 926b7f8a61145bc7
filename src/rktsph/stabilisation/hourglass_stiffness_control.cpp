#include "rktsph/stabilisation/hourglass_stiffness_control.hpp"

#include "rktsph/physics/kinematics/objective_rate.hpp"
#include "rktsph/physics/physics_model.hpp"

namespace rktsph {

HourglassStiffnessControl::HourglassStiffnessControl(const PhysicsModel& model,
                                                     const NodeSets& nodes,
                                                     HourglassStrength epsilon, bool moving)
    : stiffness_(build_hourglass_stiffness(nodes, model, epsilon)), moving_(moving) {
  if (!active()) return;
  velocity_ = {model.velocity_field(0), model.velocity_field(1)};
  force_ = FieldArray(2, nodes.stress_points.size());
  factor_.assign(nodes.stress_points.size(), 1.0);
}

void HourglassStiffnessControl::follow_flow(const CellComplex& cells,
                                            std::span<const std::uint8_t> flowing,
                                            double plastic_fraction,
                                            std::span<std::uint8_t> scratch) {
  flow_strength_factors(cells, stiffness_.near_flow, flowing, plastic_fraction, scratch, factor_);
}

void HourglassStiffnessControl::add_node_rate(const State& state, double dt, FieldArray& rate) {
  // The cells' forces at t + dt/2 (eq. 3.9), from the velocity of t^n.
  advance_hourglass_force(stiffness_, state.fields, velocity_, 0.5 * dt, factor_,
                          state.hourglass_force, force_);
  add_hourglass_acceleration(stiffness_, force_, velocity_, rate);
}

void HourglassStiffnessControl::finish(const FieldArray& mean_velocity,
                                       const FieldArray& mean_point_gradient, double dt,
                                       State& state) {
  if (moving_ && mean_point_gradient.field_count() > 0)
    rotate_forces(mean_point_gradient, dt, state.hourglass_force);
  advance_hourglass_force(stiffness_, mean_velocity, {0, 1}, dt, factor_, state.hourglass_force,
                          state.hourglass_force);
}

void HourglassStiffnessControl::rotate_forces(const FieldArray& point_velocity_gradient, double dt,
                                              FieldArray& force) const {
  // The generalised force k q of a cell is a vector of the current axes: it turns with the cell's
  // spin, as the stress does (eq. 9.2), or a rotated cell would resist hourglass modes along
  // directions it no longer has.
  const std::size_t nv = force.point_count();
  const double* dvx_dy = point_velocity_gradient.field(1);
  const double* dvy_dx = point_velocity_gradient.field(2);
  double* fx = force.field(0);
  double* fy = force.field(1);
  for (std::size_t p = 0; p < nv; ++p) {
    const PlaneRotation q = hughes_winget_rotation(0.5 * (dvx_dy[p] - dvy_dx[p]), dt);
    const double x = fx[p], y = fy[p];
    fx[p] = q.c * x + q.s * y;
    fy[p] = -q.s * x + q.c * y;
  }
}

}  // namespace rktsph
