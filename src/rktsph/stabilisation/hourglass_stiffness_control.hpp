// The cells' Flanagan-Belytschko hourglass stiffness (docs/theory.md §3.4, eqs. 3.2-3.4, 3.9,
// 3.10) as a zero-energy control of the step: the generalised forces k q of the quadrilaterals,
// carried in State::hourglass_force, act on the nodes' rates at t + dt/2 and are advanced with the
// mean velocity at the end of the step; their strength follows viscoplastic flow.
#pragma once

#include <array>
#include <vector>

#include "rktsph/stabilisation/hourglass_stiffness.hpp"
#include "rktsph/stabilisation/zero_energy_control.hpp"

namespace rktsph {

class HourglassStiffnessControl final : public ZeroEnergyControl {
 public:
  /// On the cells of `nodes` (quadrilaterals); inactive (`active()` false) in 1D or at epsilon 0.
  /// `moving`: the configuration moves, and the cells' forces turn with their spin (eq. 9.2).
  HourglassStiffnessControl(const PhysicsModel& model, const NodeSets& nodes,
                            HourglassStrength epsilon, bool moving);

  bool active() const { return stiffness_.active(); }
  const HourglassStiffness& stiffness() const { return stiffness_; }

  std::string_view name() const override { return "hourglass stiffness"; }
  bool follows_flow() const override { return true; }
  bool needs_mean_velocity() const override { return true; }
  bool carries_cell_forces() const override { return true; }
  void follow_flow(const CellComplex& cells, std::span<const std::uint8_t> flowing,
                   double plastic_fraction, std::span<std::uint8_t> scratch) override;
  void add_node_rate(const State& state, double dt, FieldArray& rate) override;
  void finish(const FieldArray& mean_velocity, const FieldArray& mean_point_gradient, double dt,
              State& state) override;

 private:
  // The forces k q turned with each cell's spin, from the stress points' gradient of the mean
  // velocity, over dt.
  void rotate_forces(const FieldArray& point_velocity_gradient, double dt, FieldArray& force) const;

  HourglassStiffness stiffness_;
  bool moving_ = false;
  std::array<int, 2> velocity_{};  // the model's velocity fields
  FieldArray force_;               // k q of every cell at t + dt/2 (eq. 3.9)
  std::vector<double> factor_;     // of eq. 3.9, from the cells' flow (eq. 3.10)
};

}  // namespace rktsph
