// Named point quantities for probes and field output: the model's unknowns ("velocity_x",
// "stress_xy"), displacements, internal variables, and invariants derived from the stress
// (pressure p = -I1/3, deviatoric stress q = sqrt(3 J2); docs/theory.md §1.3).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "rktsph/simulation/simulation.hpp"

namespace rktsph {

using NodeQuantity = std::function<double(const State& state, std::size_t node)>;

/// The quantity named `name`, or an empty function if the model has no such quantity.
NodeQuantity find_quantity(const Simulation& simulation, const std::string& name);
/// The largest speed |v| over the SPH nodes [m/s].
double largest_speed(const Simulation& simulation);
/// Every name find_quantity accepts for this simulation.
std::vector<std::string> quantity_names(const Simulation& simulation);

}  // namespace rktsph
