// Thesis §5.3.2 (docs/theory.md §8.2, §9.6): the 1D elastic bar with the large-deformation model,
// left end fixed, right end driven at -V0 (ramped over 1 ms). At mid-bar the exact small-strain
// solution is a compressive staircase (-k Z V0 from (2k-1) L/2c) and a displacement that is the
// time integral of the exact velocity. Checks:
//   front_arrival_error           when the mid-bar stress first reaches half of -Z V0, against the
//                                 exact solution's own crossing (L/2c plus half the ramp), over
//                                 L/2c. A half-level crossing, not the area under the step: the
//                                 front's overshoot (16 %) would count as early arrival there, and
//                                 the ramp as late arrival.
//   plateau_stress_error          the mean stress over the middle half of every plateau of the run
//                                 against -k Z V0; the largest relative error.
//   displacement_error            the largest |u - u_exact| at mid-bar over the run, over the
//                                 largest |u_exact|.
//   small_deformation_difference  the largest difference of the mid-bar stress history from the
//                                 small-deformation model's (dry_solid, same case), over Z V0. It
//                                 is largest inside the fronts, which the compressed bar carries
//                                 slightly faster (its Lagrangian wave speed c / sqrt(1 + eps),
//                                 docs/theory.md §9.6); it is linear in V0.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "rktsph/validation/references/elastic_bar.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::ld_bar1d_elastic {

namespace {

constexpr int kExactSamples = 4000;

/// The bar of the case file: its length, the material "soil" and the driven end's velocity.
struct Bar {
  double length = 0.0, young_modulus = 0.0, density = 0.0;
  std::optional<TimeFunction> velocity;  ///< of the right end x = L
  double end_velocity = 0.0;             ///< V0, the driven end's velocity after its ramp
  double middle = 0.0;                   ///< x of the probe group `middle`
};

Bar bar_of(const CaseDescription& description) {
  Bar bar;
  const ShapeSpec& segment = description.geometry.shapes.at(0);
  bar.length = segment.vertices.at(1)[0] - segment.vertices.at(0)[0];
  bar.young_modulus = material_parameter(description, "soil", "young_modulus");
  bar.density = material_parameter(description, "soil", "density");
  for (const BoundaryConditionSpec& condition : description.boundary_conditions)
    if (condition.group == "xmax" && condition.velocity[0]) bar.velocity = *condition.velocity[0];
  if (!bar.velocity) throw RunError("case " + description.name + ": no velocity condition on xmax");
  bar.end_velocity = (*bar.velocity)(description.time.end);
  if (bar.end_velocity == 0.0)
    throw RunError("case " + description.name + ": the driven end is at rest at the end");
  const auto middle = std::find_if(description.groups.begin(), description.groups.end(),
                                   [](const GroupSpec& g) { return g.name == "middle"; });
  if (middle == description.groups.end() || middle->kind != GroupSpec::Kind::Point)
    throw RunError("case " + description.name + ": no point group 'middle'");
  bar.middle = middle->point[0];
  return bar;
}

// The exact displacement at x by the trapezoidal rule, on steps of 1/20000 of a transit (the
// bundled ramp, 1 ms, spans 447 of them).
std::vector<double> exact_displacement(const references::ElasticBar& exact, double x,
                                       const std::vector<double>& times) {
  std::vector<double> u(times.size(), 0.0);
  double t = 0.0, integral = 0.0;
  const double h = exact.length() / exact.wave_speed() / 20000.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    while (t + h <= times[k]) {
      integral += 0.5 * h * (exact.velocity(x, t) + exact.velocity(x, t + h));
      t += h;
    }
    const double rest = times[k] - t;
    u[k] = integral + 0.5 * rest * (exact.velocity(x, t) + exact.velocity(x, times[k]));
  }
  return u;
}

// Whether `value` has reached `level` (beyond it on the side of its sign).
bool reached(double value, double level) {
  return level < 0.0 ? value <= level : value >= level;
}

// The first time a history reaches `level`, linear between samples; NaN if it never does.
double first_crossing(const std::vector<double>& time, const std::vector<double>& value,
                      double level) {
  for (std::size_t k = 1; k < time.size(); ++k)
    if (reached(value[k], level) && !reached(value[k - 1], level))
      return time[k - 1] +
             (level - value[k - 1]) / (value[k] - value[k - 1]) * (time[k] - time[k - 1]);
  return std::numeric_limits<double>::quiet_NaN();
}

// The exact stress's first crossing of `level` at x before `until`, to 1e-9 of a transit.
double exact_crossing(const references::ElasticBar& exact, double x, double level, double until) {
  double low = 0.0, high = until;
  if (!reached(exact.stress(x, high), level)) return std::numeric_limits<double>::quiet_NaN();
  // The first front rises monotonically, so the history crosses the level once before `until`.
  while (high - low > 1e-9 * until) {
    const double mid = 0.5 * (low + high);
    (reached(exact.stress(x, mid), level) ? high : low) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace

std::vector<CheckResult> validate_ld_bar1d_elastic(const ValidationContext& context) {
  const Bar bar = bar_of(load_bundled_case(context, "ld-bar1d-elastic", {}));
  const TimeFunction velocity = *bar.velocity;
  const references::ElasticBar exact(
      bar.length, bar.young_modulus, bar.density, references::BarEnd::fixed_end(),
      references::BarEnd::velocity([velocity](double t) { return velocity(t); }));
  // The first step of the staircase, Z V0 (compressive for the bundled V0 < 0), and its size.
  const double c = exact.wave_speed(), first_step = exact.impedance() * bar.end_velocity;
  const double zv0 = std::abs(first_step);
  const double transit = bar.length / c;
  const double end = context.quick ? 4.0 * transit : 8.0 * transit;
  const CaseDescription large =
      load_bundled_case(context, "ld-bar1d-elastic", {{"time.end", fmt::format("{:.17g}", end)}});
  const CaseDescription small =
      load_bundled_case(context, "ld-bar1d-elastic",
                        {{"time.end", fmt::format("{:.17g}", end)}, {"model", "dry_solid"}});
  const auto large_run = run_for_validation(context, large, "large_deformation");
  const auto small_run = run_for_validation(context, small, "small_deformation");
  const ProbeTable probes = ProbeTable::read(large_run / "probes.csv");
  const ProbeTable reference = ProbeTable::read(small_run / "probes.csv");
  const std::string stress = "middle.stress_xx";
  const double middle = bar.middle;

  const double arrival = first_crossing(probes.time(), probes.column(stress), 0.5 * first_step);
  const double exact_arrival = exact_crossing(exact, middle, 0.5 * first_step, transit);
  double plateau_error = 0.0;
  for (int k = 1; (2 * k + 1) * 0.5 * transit <= end; ++k) {
    // Plateau k lasts from (2k-1) L/2c to (2k+1) L/2c; its middle half.
    const double mean = probes.mean(stress, (k - 0.25) * transit, (k + 0.25) * transit);
    plateau_error = std::max(plateau_error, relative_error(mean, k * first_step));
  }
  const auto& time = probes.time();
  const auto& u = probes.column("middle.displacement_x");
  const std::vector<double> u_exact = exact_displacement(exact, middle, time);
  double largest_error = 0.0, largest_exact = 0.0;
  for (std::size_t k = 0; k < time.size(); ++k) {
    largest_error = std::max(largest_error, std::abs(u[k] - u_exact[k]));
    largest_exact = std::max(largest_exact, std::abs(u_exact[k]));
  }
  const auto& small_stress = reference.column(stress);
  const auto& large_stress = probes.column(stress);
  double difference = 0.0;
  for (std::size_t k = 0; k < time.size() && k < small_stress.size(); ++k)
    difference = std::max(difference, std::abs(large_stress[k] - small_stress[k]) / zv0);
  if (context.report) {
    context.report->describe(fmt::format(
        "Thesis 5.3.2: the 1D elastic bar (L = {:g} m, E = {:g} MPa, rho = {:g} kg/m3, dx = {:g} "
        "m) with the large-deformation model: nodes move, operators are rebuilt every step. Left "
        "end fixed, right end driven at {:g} m/s. Mid-bar stress is a compressive staircase of "
        "steps Z V0 = {:.3g} kPa; the displacement follows the exact one. The small-deformation "
        "model on the same bar differs by at most {:.3g} Z V0, inside the fronts, which the "
        "compressed bar carries slightly faster (a finite-strain effect, linear in V0).",
        bar.length, bar.young_modulus * 1e-6, bar.density, large.geometry.spacing, bar.end_velocity,
        zv0 * 1e-3, difference));
    Figure stress_figure{
        "mid_bar_stress", "Stress at mid-bar", "time [s]", "stress sigma_xx at x = L/2 [kPa]", {}};
    auto scaled = [](std::string label, const std::vector<double>& t, const std::vector<double>& y,
                     double factor, std::string style) {
      Series s{std::move(label), t, y, std::move(style)};
      for (double& v : s.y)
        v *= factor;
      return s;
    };
    stress_figure.series.push_back(scaled("large deformation", time, large_stress, 1e-3, "line"));
    stress_figure.series.push_back(
        scaled("small deformation", reference.time(), small_stress, 1e-3, "points"));
    stress_figure.series.push_back(sample_curve("exact", 0.0, end, kExactSamples, [&](double t) {
      return 1e-3 * exact.stress(middle, t);
    }));
    Figure displacement_figure{
        "mid_bar_displacement", "Displacement at mid-bar", "time [s]", "u_x at x = L/2 [mm]", {}};
    displacement_figure.series.push_back(scaled("large deformation", time, u, 1e3, "line"));
    displacement_figure.series.push_back(scaled("exact", time, u_exact, 1e3, "dashed"));
    context.report->add_figure(std::move(stress_figure));
    context.report->add_figure(std::move(displacement_figure));
    context.report->add_picture({"stress_end", large_run.string(), "stress", 0, -1.0, 1.0,
                                 "sigma_xx along the bar at the end, on the moved nodes"});
  }
  return {
      check_at_most("front_arrival_error", std::abs(arrival - exact_arrival) / (0.5 * transit), 0.0,
                    0.01, "fraction"),
      check_at_most("plateau_stress_error", plateau_error, 0.0, 0.02, "fraction"),
      check_at_most("displacement_error", largest_error / largest_exact, 0.0, 0.02, "fraction"),
      check_at_most("small_deformation_difference", difference, 0.0, 0.01, "fraction"),
  };
}

}  // namespace rktsph::case_checks::ld_bar1d_elastic
