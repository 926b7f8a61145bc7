// The strain hourglass stiffness (docs/theory.md §3.4; received form eqs. 3.5-3.8 on the lattice,
// patch form eqs. 3.12-3.14 on triangles) as a zero-energy control of the step: stress added at
// the stress points before the nodes' gradient of the half-step values, and, in the received form,
// the strain the nodal stress received integrated in State::strain.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "rktsph/stabilisation/strain_hourglass_stiffness.hpp"
#include "rktsph/stabilisation/zero_energy_control.hpp"

namespace rktsph {

class StrainStiffnessControl final : public ZeroEnergyControl {
 public:
  /// `to_points` is the step's table from the nodes to the stress points (kept by reference: the
  /// step rebuilds it in place), the other arguments as StrainHourglassStiffness's.
  StrainStiffnessControl(const PhysicsModel& model, const WeightTable& to_points,
                         std::span<const double> point_volume,
                         std::span<const std::uint8_t> mirror_axes,
                         std::span<const std::pair<std::int32_t, int>> constrained,
                         const NodeSets& nodes, double epsilon, StrainControl form);

  bool active() const { return stiffness_.active(); }
  const StrainHourglassStiffness& stiffness() const { return stiffness_; }

  std::string_view name() const override { return "strain hourglass stiffness"; }
  /// The patch form follows viscoplastic flow (eq. 3.14) where a material can flow.
  bool follows_flow() const override { return !factor_.empty(); }
  bool carries_received_strain() const override { return stiffness_.needs_received_strain(); }
  /// The fields and the displacement of the start: at t = 0, or when the cells were formed again
  /// (docs/theory.md §9.17), from which the control measures the displacement.
  void start(const State& state) override;
  void follow_flow(const CellComplex& cells, std::span<const std::uint8_t> flowing,
                   double plastic_fraction, std::span<std::uint8_t> scratch) override;
  void correct_half_step(const State& state, const FieldArray& point_gradient, double dt,
                         FieldArray& half_step) override;
  void record_strain_rate(const FieldArray& node_gradient, double dt, State& state) override;

 private:
  const PhysicsModel& model_;
  const NodeSets& nodes_;
  const WeightTable& to_points_;
  StrainHourglassStiffness stiffness_;
  std::vector<double> near_flow_;  // r_P of the patch form (eq. 3.14)
  std::vector<double> factor_;     // of the patch form, empty unless it follows flow (eq. 3.14)
  // Cells formed again (§9.17): the displacement at forming, and the scratch of the displacement
  // since; both empty while the start's displacement is zero.
  FieldArray start_displacement_;
  FieldArray since_start_;
};

}  // namespace rktsph
