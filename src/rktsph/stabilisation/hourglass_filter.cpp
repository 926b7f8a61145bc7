#include "rktsph/stabilisation/hourglass_filter.hpp"

#include <algorithm>

#include "rktsph/core/parallel.hpp"
#include "rktsph/physics/physics_model.hpp"
#include "rktsph/sph/operators.hpp"

namespace rktsph {

HourglassFilter::HourglassFilter(const PhysicsModel& model, const WeightTable& to_points,
                                 const WeightTable& to_nodes, HourglassFields fields, double kappa,
                                 std::size_t stress_points, std::size_t nodes)
    : model_(model), to_points_(to_points), to_nodes_(to_nodes), fields_(fields), kappa_(kappa) {
  const int nf = model.field_count();
  std::vector<std::uint8_t> is_velocity(static_cast<std::size_t>(nf), 0);
  for (int a = 0; a < model.dimension(); ++a)
    is_velocity[static_cast<std::size_t>(model.velocity_field(a))] = 1;
  for (int f = 0; f < nf; ++f) {
    if (fields_ != HourglassFields::All && model.feeds_momentum_only(f)) continue;
    const Parity parity = model.parities()[static_cast<std::size_t>(f)];
    filtered_fields_.push_back(f);
    filtered_parities_.push_back(parity);
    const bool velocity = is_velocity[static_cast<std::size_t>(f)] != 0;
    (velocity ? velocity_fields_ : other_fields_).push_back(f);
    (velocity ? velocity_parities_ : other_parities_).push_back(parity);
  }
  const std::size_t values = filtered_fields_.size();
  values_.assign(values * nodes, 0.0);
  points_.assign(values * stress_points, 0.0);
  round_trip_.assign(values * nodes, 0.0);
  if (model.pore_pressure_field() >= 0 && fields_ == HourglassFields::All)
    pore_buffer_.assign(nodes, 0.0);
}

void HourglassFilter::shift_normal_stress(FieldArray& fields, double sign) const {
  const double alpha = model_.biot_coefficient();
  const std::size_t nodes = pore_buffer_.size();
  for (int a = 0; a < 3; ++a) {
    const int f = model_.stress_field(a, a);
    if (f < 0) continue;
    double* stress = fields.field(f);
    for (std::size_t i = 0; i < nodes; ++i)
      stress[i] += sign * alpha * pore_buffer_[i];
  }
}

bool HourglassFilter::filter(FilteredPart part, FieldArray& fields) {
  if (part == FilteredPart::OtherFields && fields_ != HourglassFields::All) return false;
  // Saturated model: sigma' and p_w both jump at a drained face while the total stress does not;
  // filtering them separately spreads that boundary layer and drains undrained soil. So the
  // filter acts on the total normal stress sigma'_aa - alpha p_w and leaves p_w untouched
  // (docs/theory.md §6.5).
  const int pore = fields_ == HourglassFields::All && part != FilteredPart::Velocity
                       ? model_.pore_pressure_field()
                       : -1;
  const std::vector<int>& list = part == FilteredPart::All        ? filtered_fields_
                                 : part == FilteredPart::Velocity ? velocity_fields_
                                                                  : other_fields_;
  const std::vector<Parity>& parities = part == FilteredPart::All        ? filtered_parities_
                                        : part == FilteredPart::Velocity ? velocity_parities_
                                                                         : other_parities_;
  // Nothing to filter still counts as a pass: the step imposes the conditions again either way.
  if (list.empty()) return true;
  const std::size_t count_nodes = fields.point_count();
  if (pore >= 0) {
    std::copy_n(fields.field(pore), count_nodes, pore_buffer_.begin());
    shift_normal_stress(fields, -1.0);
  }

  // f <- f - kappa (r1 - Pi r1), r1 = f - Pi f, Pi = round trip through the stress points
  // (docs/theory.md §3.3; symbol 1 - kappa (1 - a^2)^2, removes the checkerboard).
  // The round trip works on node-major (interleaved) copies: its gathers reach ~21 sources per
  // row, and one cache line then brings all the fields of a source (3x faster on large lattices).
  const auto nf = static_cast<int>(list.size());
  const int* filtered = list.data();
  const auto nodes = static_cast<std::int64_t>(count_nodes);
  auto round_trip = [&](const std::vector<double>& in) {
    apply_interpolation_interleaved(to_points_, in, parities, points_);
    apply_interpolation_interleaved(to_nodes_, points_, parities, round_trip_);
  };
  double* values = values_.data();
#pragma omp parallel for schedule(static) if (nodes > kParallelThreshold)
  for (std::int64_t i = 0; i < nodes; ++i)
    for (int f = 0; f < nf; ++f)
      values[i * nf + f] = fields.field(filtered[f])[i];
  round_trip(values_);
  // The residual in place of the copies: the fields still hold the values.
  double* residual = values_.data();
  const double* trip = round_trip_.data();
  const auto count = nodes * nf;
#pragma omp parallel for schedule(static) if (count > kParallelThreshold)
  for (std::int64_t k = 0; k < count; ++k)
    residual[k] = values[k] - trip[k];
  round_trip(values_);
  const double kappa = kappa_;
#pragma omp parallel for schedule(static) if (nodes > kParallelThreshold)
  for (std::int64_t i = 0; i < nodes; ++i)
    for (int f = 0; f < nf; ++f) {
      double& value = fields.field(filtered[f])[i];
      value = value - kappa * (residual[i * nf + f] - trip[i * nf + f]);
    }
  if (pore >= 0) {
    std::copy_n(pore_buffer_.begin(), count_nodes, fields.field(pore));
    shift_normal_stress(fields, 1.0);
  }
  return true;
}

}  // namespace rktsph
