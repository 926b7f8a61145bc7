#include "rktsph/time/zero_energy_controls.hpp"

#include "rktsph/stabilisation/hourglass_filter.hpp"
#include "rktsph/stabilisation/hourglass_stiffness_control.hpp"
#include "rktsph/stabilisation/strain_stiffness_control.hpp"
#include "rktsph/time/configuration_policy.hpp"

namespace rktsph {

ZeroEnergyControls make_zero_energy_controls(const PhysicsModel& model, const NodeSets& reference,
                                             const StepOptions& options,
                                             const StepOperators& operators, bool filter_active,
                                             const BoundaryConditions& conditions,
                                             const Configuration& configuration,
                                             const ConfigurationPolicy& policy) {
  ZeroEnergyControls controls;
  if (filter_active) {
    // With wider stencils the velocity-only filter leaves the step unstable (spectral radius
    // 1.00003-1.001 at h = 1.0-1.3 dx); the filter on every field keeps it below 1 (§3.3). Fixed
    // at the first build, so that a rebuild never switches the filtered fields.
    const HourglassFields fields = options.hourglass_fields.value_or(
        operators.compact_stencils ? HourglassFields::Velocity : HourglassFields::All);
    controls.push_back(std::make_unique<HourglassFilter>(
        model, operators.filter_to_points, operators.filter_to_nodes, fields,
        options.hourglass_kappa, reference.stress_points.size(), reference.sph_nodes.size()));
  }
  auto cells = std::make_unique<HourglassStiffnessControl>(
      model, reference, options.hourglass_stiffness, policy.motion() != nullptr);
  if (cells->active()) controls.push_back(std::move(cells));
  // On the first tables: it keeps the imposed stresses of t = 0 as its reference (eq. 3.8).
  auto strain = std::make_unique<StrainStiffnessControl>(
      model, operators.nodes_to_points, configuration.stress_points.volume,
      conditions.mirror_axes(), conditions.constrained_stress(), reference,
      options.strain_hourglass_stiffness, options.strain_control);
  if (strain->active()) controls.push_back(std::move(strain));
  return controls;
}

}  // namespace rktsph
