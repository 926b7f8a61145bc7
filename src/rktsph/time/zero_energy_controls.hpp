// The zero-energy controls of a step, made from its options (docs/theory.md §3.3-§3.4): the
// hourglass filter where the operator builder builds its tables, the cells' Flanagan-Belytschko
// stiffness where epsilon > 0 (quadrilaterals), the strain stiffness in its received or patch form
// where epsilon_s or beta > 0. Inactive controls are left out, so the step calls only what acts.
#pragma once

#include <memory>
#include <vector>

#include "rktsph/boundary/boundary_conditions.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/physics/configuration.hpp"
#include "rktsph/stabilisation/zero_energy_control.hpp"
#include "rktsph/time/step_operators.hpp"

namespace rktsph {

class ConfigurationPolicy;
class PhysicsModel;

using ZeroEnergyControls = std::vector<std::unique_ptr<ZeroEnergyControl>>;

/// `operators` are the step's first tables (kept by reference by the controls that read them),
/// `filter_active` whether the builder builds the filter's tables, `conditions` give the mirror
/// planes and the imposed stresses of the strain stiffness, `configuration` the stress points'
/// volumes, `policy` whether the configuration moves (the cells' forces then turn with their spin).
ZeroEnergyControls make_zero_energy_controls(const PhysicsModel& model, const NodeSets& reference,
                                             const StepOptions& options,
                                             const StepOperators& operators, bool filter_active,
                                             const BoundaryConditions& conditions,
                                             const Configuration& configuration,
                                             const ConfigurationPolicy& policy);

}  // namespace rktsph
