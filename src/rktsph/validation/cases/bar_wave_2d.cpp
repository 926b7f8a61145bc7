// BAR-WAVE-2D (docs/theory.md §8.11): a plane P-wave in a 2D lattice, run with the
// artificial viscosity (docs/theory.md §2.7, alpha = 0.25) and without it. Exact solution: front at
// c_p, sigma_xx = -rho c_p V0 behind it, v_y = 0 everywhere, tension +rho c_p V0 after the
// reflections.
#include <fmt/format.h>

#include <cmath>

#include "rktsph/validation/references/elastic_bar.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::bar_wave_2d {

namespace {

struct BarWaveMetrics {
  double arrival_dx;  // signed lag of the mid-bar front, in dx / c_p
  double plateau;     // relative error of the mean sigma_xx plateau
  double overshoot;   // of v_x at mid-bar before 1.3 L/c_p
  double max_vy;      // max |v_y| / V0 over all nodes and steps
  double tension;     // relative error of the mean tension plateau
  double growth;      // peak |sigma_xx| over the last third of the run / the middle third
  // For the report.
  std::filesystem::path run_directory;
  ProbeTable probes;
};

constexpr double kLength = 1.0, kDensity = 2000.0, kWaveSpeed = 300.0, kPistonVelocity = 0.3;
constexpr double kTransit = kLength / kWaveSpeed;

/// `field_interval` [s]: time between field outputs, 0 for the first and last only; `extra`:
/// further overrides (a variant's spacing).
BarWaveMetrics measure(const ValidationContext& context, const std::string& folder,
                       double viscosity, double end_transits, const std::string& label,
                       double field_interval = 0.0, const std::vector<CaseOverride>& extra = {}) {
  const double c = kWaveSpeed, v0 = kPistonVelocity, impedance = kDensity * c;
  const double transit = kTransit;
  std::vector<CaseOverride> overrides = {
      {"numerics.artificial_viscosity", std::to_string(viscosity)},
      {"time.end", std::to_string(end_transits * transit)},
      {"output.interval", fmt::format("{:.17g}", field_interval)}};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  CaseDescription description = load_bundled_case(context, folder, overrides);
  const double dx = description.geometry.spacing;
  BarWaveMetrics m{};
  m.run_directory = run_for_validation(context, description, label);
  m.probes = ProbeTable::read(m.run_directory / "probes.csv");
  const ProbeTable& probes = m.probes;
  m.arrival_dx = (probes.first_crossing("mid.velocity_x", 0.5 * v0) - 0.5 * transit) / (dx / c);
  m.plateau =
      relative_error(probes.mean("mid.stress_xx", 0.75 * transit, 1.3 * transit), -impedance * v0);
  m.overshoot = probes.max("mid.velocity_x", 0.0, 1.3 * transit) / v0 - 1.0;
  m.max_vy = probes.max_abs("all.velocity_y", 0.0, end_transits * transit) / v0;
  if (end_transits < 2.95) return m;  // a run too short for the tension and the growth
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

Series scaled(std::string label, const ProbeTable& probes, const std::string& column,
              double scale) {
  Series curve{std::move(label), probes.time(), probes.column(column), "line"};
  for (double& y : curve.y)
    y *= scale;
  return curve;
}

/// v_x and sigma_xx at mid-bar against the exact plane wave (`without`: the run without
/// artificial viscosity, if there is one), and a picture of the front.
void add_bar_wave_figures(ValidationReport& report, const BarWaveMetrics& with,
                          const BarWaveMetrics* without) {
  // With rollers top and bottom the lattice is in uniaxial strain, so the 1D bar solution holds
  // with the P-wave modulus rho c_p^2 in place of E: piston (velocity V0) at x = 0, free x = L.
  const references::ElasticBar exact(
      kLength, kDensity * kWaveSpeed * kWaveSpeed, kDensity,
      references::BarEnd::velocity([](double) { return kPistonVelocity; }),
      references::BarEnd::free_end());
  const double end = with.probes.time().back();
  const double mid = 0.5 * kLength;
  // 4000 samples: the exact steps are vertical at report size.
  Figure velocity{"mid_velocity",
                  "v_x at mid-bar (column x = L/2)",
                  "time [s]",
                  "velocity v_x [m/s]",
                  {scaled("SPH with AV (alpha = 0.25)", with.probes, "mid.velocity_x", 1.0)}};
  Figure stress{"mid_stress",
                "sigma_xx at mid-bar (column x = L/2)",
                "time [s]",
                "stress sigma_xx [kPa]",
                {scaled("SPH with AV (alpha = 0.25)", with.probes, "mid.stress_xx", 1e-3)}};
  if (without) {
    velocity.series.push_back(scaled("SPH without AV", without->probes, "mid.velocity_x", 1.0));
    stress.series.push_back(scaled("SPH without AV", without->probes, "mid.stress_xx", 1e-3));
  }
  velocity.series.push_back(
      sample_curve("exact", 0.0, end, 4000, [&](double t) { return exact.velocity(mid, t); }));
  stress.series.push_back(
      sample_curve("exact", 0.0, end, 4000, [&](double t) { return 1e-3 * exact.stress(mid, t); }));
  report.add_figure(std::move(velocity));
  report.add_figure(std::move(stress));
  report.add_picture({"stress_front", with.run_directory.string(), "stress", 0, 0.75 * kTransit,
                      50.0,
                      "sigma_xx with AV at t = 0.75 L/c_p on the cells deformed 50 times: the "
                      "compressed three quarters behind the front at -rho c_p V0 = -180 kPa, "
                      "the rest at rest."});
}

void report_bar_wave(ValidationReport& report, const std::string& folder,
                     const BarWaveMetrics& with, const BarWaveMetrics& without) {
  report.describe(
      "BAR-WAVE-2D: a plane P-wave in a 2D plane-strain lattice (L = 1 m, c_p = 300 m/s), "
      "driven by a piston at x = 0 with V0 = 0.3 m/s, free at x = L, rollers top and bottom; "
      "lattice " +
      folder +
      ". Run with the artificial viscosity (alpha = 0.25) and without it. "
      "Exact: a step of v_x = V0 and sigma_xx = -rho c_p V0 reaching mid-bar at L/2c_p, doubled "
      "velocity after the free-end reflection, tension after the piston reflection; v_y = 0.");
  add_bar_wave_figures(report, with, &without);
}

/// The relative L2 error of the smooth plane wave on triangles against dx, with slope 2.
void add_convergence_figure(ValidationReport& report,
                            const convergence::PlaneWaveConvergence& refined) {
  Figure errors{"error_vs_dx",
                "Smooth plane wave on triangles: relative L2 error of sigma_xx at 0.9 L/c_p",
                "dx (longest edge) [m]",
                "relative L2 error [-]",
                {{fmt::format("triangles (fitted order {:.2f})", refined.order), refined.spacing,
                  refined.error, "points"}}};
  const double x0 = refined.spacing.front(), x1 = refined.spacing.back();
  const double e0 = 0.5 * refined.error.front();
  errors.series.push_back(
      {"slope 2 (expected order)", {x0, x1}, {e0, e0 * (x1 / x0) * (x1 / x0)}, "dashed"});
  errors.x_scale = "log";
  errors.y_scale = "log";
  report.add_figure(std::move(errors));
}

}  // namespace

std::vector<CheckResult> validate_bar_wave_2d(const ValidationContext& context) {
  const std::string folder = context.quick ? "bar-wave-2d-t" : "bar-wave-2d-s";
  // Field output every quarter transit only when reporting, for the picture of the front.
  const BarWaveMetrics with =
      measure(context, folder, 0.25, 3.0, "with-av", context.report ? 0.25 * kTransit : 0.0);
  const BarWaveMetrics without = measure(context, folder, 0.0, 3.0, "no-av");
  // Long run on the small lattice: no growth of the peak stress per transit over 12 L/c_p
  // (6 in the quick variant).
  const BarWaveMetrics long_run =
      measure(context, "bar-wave-2d-t", 0.0, context.quick ? 6.0 : 12.0, "long-no-av");
  if (context.report) report_bar_wave(*context.report, folder, with, without);
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
      check_at_most(
          context.quick ? "peak_growth_ratio_6_transits" : "peak_growth_ratio_12_transits",
          long_run.growth, 1.0, 1.02, "ratio"),
  };
}

// triangles-bar-wave-2d (issue 28; docs/theory.md §8.11): the same plane wave on a triangle mesh,
// run with the artificial viscosity to 1.3 L/c_p (the plateau, the arrival and the sideways
// motion), and the smooth plane wave of `convergence` refined on triangles. The quick variant
// takes edges up to 10 mm (size T) and three levels.
std::vector<CheckResult> validate_triangles_bar_wave_2d(const ValidationContext& context) {
  const std::string folder = "triangles-bar-wave-2d";
  std::vector<CaseOverride> spacing;
  if (context.quick) spacing.push_back({"geometry.spacing", "0.01"});
  const BarWaveMetrics with = measure(context, folder, 0.25, 1.3, "with-av",
                                      context.report ? 0.25 * kTransit : 0.0, spacing);
  const std::vector<int> cells =
      context.quick ? std::vector<int>{40, 80, 160} : std::vector<int>{40, 80, 160, 320};
  const convergence::PlaneWaveConvergence refined =
      convergence::plane_wave_convergence(context, cells, {{"geometry.cells", "triangles"}});
  if (context.report) {
    context.report->describe(
        "BAR-WAVE-2D on a triangle mesh: the plane P-wave of bar-wave-2d-s (L = 1 m, c_p = "
        "300 m/s, piston V0 = 0.3 m/s at x = 0, free at x = L, rollers top and bottom) with "
        "triangles of edges at most dx, run with the artificial viscosity (alpha = 0.25) to "
        "1.3 L/c_p; and the smooth pulse of `convergence` in a strip 4 dx high meshed with "
        "triangles, refined at Courant 0.5 (expected order 2). An unstructured mesh is not "
        "symmetric about the bar's axis, so v_y is not zero to rounding as on the lattice.");
    add_bar_wave_figures(*context.report, with, nullptr);
    add_convergence_figure(*context.report, refined);
  }
  return {
      check_at_most("arrival_error_dx", std::abs(with.arrival_dx), 0.0, 1.0, "dx/c_p"),
      check_at_most("sigma_xx_plateau_error", with.plateau, 0.0, 0.01, "fraction"),
      check_at_most("max_vy_ratio", with.max_vy, 0.0, 1e-3, "fraction"),
      convergence::convergence_order_check("convergence_order_wave2d", refined.order),
  };
}

}  // namespace rktsph::case_checks::bar_wave_2d
