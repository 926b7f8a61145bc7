// Thesis §4.2, validation.md §4.2: the 1D elastic bar at Courant 0.6 and 1.0 against the exact
// characteristics solution: a -Z V0 compression plateau at mid-bar from L/2c, unloading at 3L/2c,
// a +Z V0 tension plateau from 5L/2c, period 4L/c, no growth.
#include <cmath>

#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph {

std::vector<CheckResult> validate_bar1d_elastic(const ValidationContext& context) {
  const double length = 10.0, density = 2000.0, young = 1e8, v0 = 0.1;  // as in case.yaml
  const double c = std::sqrt(young / density), impedance = density * c;
  const double transit = length / c, period = 4.0 * transit;
  const int periods = context.quick ? 5 : 6;  // the growth check needs >= 5 periods

  double arrival_error = 0.0, plateau_error = 0.0, tension_error = 0.0;
  double overshoot[2] = {0.0, 0.0}, growth[2] = {0.0, 0.0};
  const double courants[2] = {0.6, 1.0};
  for (int run = 0; run < 2; ++run) {
    const std::string label = run == 0 ? "c06" : "c10";
    const CaseDescription description = load_bundled_case(
        context, "bar1d-elastic",
        {{"numerics.courant", std::to_string(courants[run])},
         {"time.end", std::to_string(periods * period)},
         {"output.interval", std::to_string(period / 8.0)}});
    const ProbeTable probes = ProbeTable::read(run_for_validation(context, description, label) /
                                               "probes.csv");
    const std::string stress = "middle.stress_xx";
    // Arrival of the first front at mid-bar, from the area under the step (exact: L/2c).
    const double arrival = probes.step_arrival(stress, -impedance * v0, 0.0, transit);
    arrival_error = std::max(arrival_error, relative_error(arrival, 0.5 * transit));
    // Plateaux, over the middle half of each: the first compression plateau in (L/2c, 3L/2c),
    // and the tension plateau in (5L/2c, 7L/2c), reached after two more reflections, which carries
    // the Lax-Wendroff ringing they add (3 % at C = 0.6 on 20 cells; none at C = 1).
    const double compression = probes.mean(stress, 0.75 * transit, 1.25 * transit);
    const double tension = probes.mean(stress, 2.75 * transit, 3.25 * transit);
    plateau_error = std::max(plateau_error, relative_error(compression, -impedance * v0));
    tension_error = std::max(tension_error, relative_error(tension, impedance * v0));
    // Overshoot of the first plateau (before the unloading front at 3L/2c).
    overshoot[run] = probes.max_abs(stress, 0.0, 1.5 * transit) / (impedance * v0) - 1.0;
    // Peak |sigma| over the last period against the first.
    growth[run] = probes.max_abs(stress, (periods - 1) * period, periods * period) /
                  probes.max_abs(stress, 0.0, period);
  }
  return {
      check_at_most("front_arrival_error", arrival_error, 0.0, 0.01, "fraction"),
      check_at_most("plateau_stress_error", plateau_error, 0.0, 0.02, "fraction"),
      check_at_most("tension_plateau_error", tension_error, 0.0, 0.05, "fraction"),
      check_at_most("overshoot_c06", overshoot[0], 0.0, 0.22, "fraction"),
      check_at_most("overshoot_c10", overshoot[1], 0.0, 0.05, "fraction"),
      check_at_most("peak_growth_ratio_c06", growth[0], 1.0, 1.02, "ratio"),
      check_at_most("peak_growth_ratio_c10", growth[1], 1.0, 1.02, "ratio"),
  };
}

}  // namespace rktsph
