// BAR-WAVE-2D (../shared/bench/bar-wave-2d.md): a plane P-wave in a 2D lattice, run with the
// artificial viscosity (prototype R7, alpha = 0.25) and without it. Exact solution: front at c_p,
// sigma_xx = -rho c_p V0 behind it, v_y = 0 everywhere, tension +rho c_p V0 after the reflections.
#include <cmath>

#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph {

namespace {

struct BarWaveMetrics {
  double arrival_dx;  // signed lag of the mid-bar front, in dx / c_p
  double plateau;     // relative error of the mean sigma_xx plateau
  double overshoot;   // of v_x at mid-bar before 1.3 L/c_p
  double max_vy;      // max |v_y| / V0 over all nodes and steps
  double tension;     // relative error of the mean tension plateau
  double growth;      // peak |sigma_xx| over the last third of the run / the middle third
};

BarWaveMetrics measure(const ValidationContext& context, const std::string& folder,
                       double viscosity, double end_transits, const std::string& label) {
  const double length = 1.0, c = 300.0, v0 = 0.3, impedance = 2000.0 * c, transit = length / c;
  CaseDescription description = load_bundled_case(
      context, folder,
      {{"numerics.artificial_viscosity", std::to_string(viscosity)},
       {"time.end", std::to_string(end_transits * transit)},
       {"output.interval", "0"}});
  const double dx = description.geometry.spacing;
  const ProbeTable probes =
      ProbeTable::read(run_for_validation(context, description, label) / "probes.csv");
  BarWaveMetrics m{};
  m.arrival_dx = (probes.first_crossing("mid.velocity_x", 0.5 * v0) - 0.5 * transit) / (dx / c);
  m.plateau =
      relative_error(probes.mean("mid.stress_xx", 0.75 * transit, 1.3 * transit), -impedance * v0);
  m.overshoot = probes.max("mid.velocity_x", 0.0, 1.3 * transit) / v0 - 1.0;
  m.max_vy = probes.max_abs("all.velocity_y", 0.0, end_transits * transit) / v0;
  m.tension =
      relative_error(probes.mean("mid.stress_xx", 2.75 * transit, 2.95 * transit), impedance * v0);
  // Growth: the peak over the last third of the run against the middle third. The first transits
  // are left out because the dispersive ringing of the front builds up over the first reflections
  // and then saturates; an instability keeps growing geometrically.
  const double last = end_transits * transit;
  m.growth = probes.max_abs("mid.stress_xx", 2.0 * last / 3.0, last) /
             probes.max_abs("mid.stress_xx", last / 3.0, 2.0 * last / 3.0);
  return m;
}

}  // namespace

std::vector<CheckResult> validate_bar_wave_2d(const ValidationContext& context) {
  const std::string folder = context.quick ? "bar-wave-2d-t" : "bar-wave-2d-s";
  const BarWaveMetrics with = measure(context, folder, 0.25, 3.0, "with-av");
  const BarWaveMetrics without = measure(context, folder, 0.0, 3.0, "no-av");
  // Long run on the small lattice: no growth of the peak stress per transit over 12 L/c_p
  // (6 in the quick variant).
  const BarWaveMetrics long_run =
      measure(context, "bar-wave-2d-t", 0.0, context.quick ? 6.0 : 12.0, "long-no-av");
  return {
      check_at_most("arrival_error_dx", std::abs(with.arrival_dx), 0.0, 1.0, "dx/c_p"),
      check_at_most("sigma_xx_plateau_error", with.plateau, 0.0, 0.01, "fraction"),
      check_at_most("overshoot", with.overshoot, 0.0, 0.03, "fraction"),
      check_at_most("max_vy_ratio", with.max_vy, 0.0, 1e-10, "fraction"),
      check_at_most("tension_plateau_error", with.tension, 0.0, 0.02, "fraction"),
      check_at_most("overshoot_no_av", without.overshoot, 0.0, 0.25, "fraction"),
      check_at_most("sigma_xx_plateau_error_no_av", without.plateau, 0.0, 0.01, "fraction"),
      check_at_most("max_vy_ratio_no_av", without.max_vy, 0.0, 1e-10, "fraction"),
      check_at_most("tension_plateau_error_no_av", without.tension, 0.0, 0.02, "fraction"),
      check_at_most(context.quick ? "peak_growth_ratio_6_transits" : "peak_growth_ratio_12_transits", long_run.growth, 1.0, 1.02, "ratio"),
  };
}

}  // namespace rktsph
