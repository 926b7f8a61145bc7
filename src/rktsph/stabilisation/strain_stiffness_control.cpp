#include "rktsph/stabilisation/strain_stiffness_control.hpp"

#include <algorithm>

#include "rktsph/stabilisation/flow_strength.hpp"

namespace rktsph {

StrainStiffnessControl::StrainStiffnessControl(
    const PhysicsModel& model, const WeightTable& to_points, std::span<const double> point_volume,
    std::span<const std::uint8_t> mirror_axes,
    std::span<const std::pair<std::int32_t, int>> constrained, const NodeSets& nodes,
    double epsilon, StrainControl form)
    : model_(model),
      nodes_(nodes),
      to_points_(to_points),
      stiffness_(model, to_points, point_volume, mirror_axes, constrained, nodes.node_material,
                 nodes, epsilon, form) {
  // The patch form follows viscoplastic flow as the lattice's control does (eq. 3.14); with
  // elastic materials only its factors would all be 1, so none are kept.
  if (!stiffness_.active() || form != StrainControl::Patch) return;
  near_flow_ = near_flow_ratios(nodes.cells, model, kPatchNearFlowFraction);
  if (std::any_of(near_flow_.begin(), near_flow_.end(), [](double ratio) { return ratio != 1.0; }))
    factor_.assign(nodes.stress_points.size(), 1.0);
  else
    near_flow_.clear();
}

void StrainStiffnessControl::follow_flow(const CellComplex& cells,
                                         std::span<const std::uint8_t> flowing,
                                         double plastic_fraction, std::span<std::uint8_t> scratch) {
  if (!factor_.empty())
    flow_strength_factors(cells, near_flow_, flowing, plastic_fraction, scratch, factor_);
}

void StrainStiffnessControl::start(const State& state) {
  stiffness_.set_reference(state.fields);
  // On cells formed again the patches are the new cells': the strain they fit is that of the
  // displacement since the forming, which the cells have followed, not since the start, which a
  // large deformation has made non-linear on them (docs/theory.md §9.17).
  const FieldArray& u = state.displacement;
  const bool moved =
      std::any_of(u.data().begin(), u.data().end(), [](double x) { return x != 0.0; });
  if (!moved) return;
  start_displacement_ = u;
  since_start_ = FieldArray(u.field_count(), u.point_count());
}

void StrainStiffnessControl::correct_half_step(const State& state, const FieldArray& point_gradient,
                                               double dt, FieldArray& half_step) {
  const FieldArray* displacement = &state.displacement;
  if (since_start_.point_count() > 0) {
    const std::vector<double>& now = state.displacement.data();
    const std::vector<double>& start = start_displacement_.data();
    std::vector<double>& since = since_start_.data();
    for (std::size_t k = 0; k < since.size(); ++k)
      since[k] = now[k] - start[k];
    displacement = &since_start_;
  }
  stiffness_.add_stress(model_, to_points_, nodes_.cells.materials(), *displacement, state.strain,
                        point_gradient, dt, state.fields, factor_, half_step);
}

void StrainStiffnessControl::record_strain_rate(const FieldArray& node_gradient, double dt,
                                                State& state) {
  stiffness_.integrate_strain(model_, node_gradient, dt, state.strain);
}

}  // namespace rktsph
