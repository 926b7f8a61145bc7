// The hourglass filter (docs/theory.md §3.3, eq. 3.1) as a zero-energy control of the step: after
// the conditions of t + dt, every filtered nodal field f becomes f - kappa (r - Pi r), r = f - Pi
// f, Pi the first-order round trip through the stress points (symbol 1 - kappa (1 - a^2)^2), which
// removes the checkerboard and passes fields linear in x. In the saturated model it acts on the
// total normal stress and leaves p_w alone (§6.5).
#pragma once

#include <vector>

#include "rktsph/core/step_choices.hpp"
#include "rktsph/sph/operators.hpp"
#include "rktsph/stabilisation/zero_energy_control.hpp"

namespace rktsph {

class PhysicsModel;

class HourglassFilter final : public ZeroEnergyControl {
 public:
  /// `to_points` and `to_nodes` are the round trip's tables, kept by reference: the step rebuilds
  /// them in place. `fields` says which fields are filtered (every
  /// field, or those that do not only feed the momentum balance), `kappa` its strength.
  HourglassFilter(const PhysicsModel& model, const WeightTable& to_points,
                  const WeightTable& to_nodes, HourglassFields fields, double kappa,
                  std::size_t stress_points, std::size_t nodes);

  HourglassFields fields() const { return fields_; }

  std::string_view name() const override { return "hourglass filter"; }
  /// The other fields are filtered only when every field is (HourglassFields::All).
  bool filter(FilteredPart part, FieldArray& fields) override;

 private:
  void shift_normal_stress(FieldArray& fields, double sign) const;

  const PhysicsModel& model_;
  const WeightTable& to_points_;
  const WeightTable& to_nodes_;
  HourglassFields fields_;
  double kappa_;
  std::vector<int> filtered_fields_;  // by part: All, Velocity, OtherFields
  std::vector<Parity> filtered_parities_;
  std::vector<int> velocity_fields_, other_fields_;
  std::vector<Parity> velocity_parities_, other_parities_;
  // Scratch, allocated once.
  std::vector<double> values_;  // node-major copies for the round trip, then its residual
  std::vector<double> points_;
  std::vector<double> round_trip_;
  std::vector<double> pore_buffer_;  // p_w kept out of the filter (saturated model)
};

}  // namespace rktsph
