// Thesis V2-0 in small deformation: a slender elastic beam (1 m x 10 m, plane stress) clamped at
// its top, hanging under gravity ramped in over 0.2 s, mass-damped (about critical for its first
// axial mode) to rest. Checks:
//   hourglass_velocity_ratio  at every probe output, the odd-even part of v_y (the (-1)^(i+j)
//                             component from the 3x3 stencil of checkerboard_amplitude,
//                             rest_checks.hpp) over its smooth part, max |v_y|; the largest over
//                             the outputs where max |v_y| is at least kMovingFraction of its peak,
//                             nodes near the clamped corners left out (kCornerExclusion).
//   tip_displacement_error    the mean u_y of the free end at the end against the uniaxial hanging
//                             bar, rho g L^2 / (2E) (in plane stress sigma_xx = 0 and
//                             eps_yy = sigma_yy / E exactly; the clamp's lateral restraint at the
//                             top changes it by O(nu^2 W / L), a few 1e-3).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::hanging_beam {

namespace {

// Quick variant: dx = 0.25 m (4 cells across) and a shorter run.
constexpr double kQuickSpacing = 0.25, kQuickEnd = 0.6;
// The odd-even ratio is taken while the beam moves: at outputs where max |v_y| is at least 1 % of
// its peak. Later the smooth motion has been damped out and the ratio would compare the noise of
// two vanishing quantities; at 1 % an odd-even mode of 1e-5 of the peak velocity still fails the
// 1e-3 limit, which is stricter than the residual_velocity_ratio limit (1e-3 of the peak) of the
// strip cases.
constexpr double kMovingFraction = 0.01;
// Where the clamped top meets a free side the elastic field is singular (a clamped-free corner:
// stresses ~ r^(lambda-1), lambda < 1), so there the 3x3 stencil returns dx^4 |v_xxyy|/16 of the
// exact field, not small: at the first output (5 ms, the ramp just begun) it gives 2.8e-3 of
// max |v_y| from the two nodes next to each corner, with no alternation in the field. As
// vpw-strip-footing-elastic leaves out the singular footing edge, nodes within max(W/4, 3 dx) of
// the two clamped corners are left out (the rest of the rows under the clamp are kept).
constexpr double kCornerExclusion = 0.25;

struct OddEvenSample {
  double time = 0.0, oddeven = 0.0, smooth = 0.0;
};

/// The beam of the case: the first shape, clamped along its top, and the material "soil".
struct Beam {
  Rectangle body;
  double density = 0.0, gravity = 0.0, young = 0.0;
  /// sigma_yy / eps_yy of the uniaxial hanging bar (sigma_xx = 0): E in plane stress,
  /// E / (1 - nu^2) in plane strain (eps_zz = 0).
  double bar_modulus = 0.0;
};

Beam beam_of(const CaseDescription& description) {
  Beam beam;
  beam.body = rectangle_shape(description, 0);
  beam.density = material_parameter(description, "soil", "density");
  beam.gravity = downward_gravity(description);
  beam.young = material_parameter(description, "soil", "young_modulus");
  const double poisson = material_parameter(description, "soil", "poisson_ratio");
  beam.bar_modulus =
      description.plane == PlaneKind::Stress ? beam.young : beam.young / (1.0 - poisson * poisson);
  return beam;
}

}  // namespace

std::vector<CheckResult> validate_hanging_beam(const ValidationContext& context) {
  std::vector<CaseOverride> overrides;
  if (context.quick) {
    overrides.push_back({"geometry.spacing", fmt::format("{:g}", kQuickSpacing)});
    overrides.push_back({"time.end", fmt::format("{:g}", kQuickEnd)});
  }
  const CaseDescription description = load_bundled_case(context, "hanging-beam", overrides);
  const Beam beam = beam_of(description);
  const double length = beam.body.height(), width = beam.body.width();
  std::vector<OddEvenSample> samples;
  SampledObserver oddeven(description.output.probe_interval, [&](const Simulation& simulation) {
    const LatticeField vy = lattice_field(simulation, simulation.model().velocity_field(1));
    // Nodes near the clamped corners are left out: see kCornerExclusion.
    const double radius = std::max(kCornerExclusion * width, 3.0 * vy.spacing);
    samples.push_back({simulation.state().time,
                       checkerboard_amplitude(
                           vy,
                           [radius, &beam](double x, double y) {
                             const Rectangle& top = beam.body;
                             return std::min(std::hypot(x - top.x_min, y - top.y_max),
                                             std::hypot(x - top.x_max, y - top.y_max)) < radius;
                           }),
                       max_abs(vy)});
  });
  const std::filesystem::path run_directory =
      run_for_validation(context, description, context.quick ? "quick" : "full", {}, {&oddeven});
  const ProbeTable probes = ProbeTable::read(run_directory / "probes.csv");

  double peak = 0.0;
  for (const OddEvenSample& sample : samples)
    peak = std::max(peak, sample.smooth);
  double ratio = 0.0, worst_time = 0.0;
  std::vector<double> times, ratios;
  for (const OddEvenSample& sample : samples) {
    if (sample.smooth < kMovingFraction * peak) continue;
    times.push_back(sample.time);
    ratios.push_back(sample.oddeven / sample.smooth);
    if (ratios.back() > ratio) {
      ratio = ratios.back();
      worst_time = sample.time;
    }
  }
  if (times.empty()) ratio = std::numeric_limits<double>::quiet_NaN();
  const double reference = beam.density * beam.gravity * length * length / (2.0 * beam.bar_modulus);
  const double tip = -probes.column("tip.displacement_y").back();
  const double tip_error = relative_error(tip, reference);

  if (context.report) {
    ValidationReport& report = *context.report;
    report.describe(fmt::format(
        "Thesis V2-0 in small deformation: an elastic beam {:g} m wide and {:g} m long (E = {:g} "
        "MPa, nu = {:g}, rho = {:g} kg/m3, plane {}, dx = {:g} m) clamped at its top, hanging "
        "under gravity ramped in over {:g} s, with mass damping {:g}/s (about critical for the "
        "first axial mode). References: the static tip displacement of the uniaxial hanging bar, "
        "rho g L^2 / (2E) = {:.3f} mm (E / (1 - nu^2) in plane strain; measured {:.3f} mm at the "
        "end); the velocity must carry no "
        "node-to-node (odd-even) mode: the (-1)^(i+j) part of v_y over max |v_y| is at most {:.2g} "
        "(at t = {:.3f} s) over the outputs where the beam moves (max |v_y| >= {:g} of its peak), "
        "the nodes near the clamped corners (a singular corner of the elastic field) left out.",
        width, length, 1e-6 * beam.young, material_parameter(description, "soil", "poisson_ratio"),
        beam.density, description.plane == PlaneKind::Stress ? "stress" : "strain",
        description.geometry.spacing, description.gravity->factor.duration,
        description.damping ? description.damping->coefficient : 0.0, 1e3 * reference, 1e3 * tip,
        ratio, worst_time, kMovingFraction));
    Series history{"SPH, mean u_y of the free end", probes.time(), {}, "line"};
    for (double u : probes.column("tip.displacement_y"))
      history.y.push_back(-1e3 * u);
    report.add_figure(
        {"tip_displacement",
         "Tip displacement against time",
         "time [s]",
         "tip displacement -u_y [mm]",
         {std::move(history), sample_curve("static rho g L^2 / (2E)", 0.0, probes.time().back(), 2,
                                           [&](double) { return 1e3 * reference; })}});
    Figure oddeven_figure{
        "oddeven_ratio",
        "Odd-even part of v_y over max |v_y| while the beam moves",
        "time [s]",
        "(-1)^(i+j) part of v_y / max |v_y|",
        {{"SPH", times, positive_or_nan(ratios), "points"},
         sample_curve("limit 1e-3", 0.0, probes.time().back(), 2, [](double) { return 1e-3; })}};
    oddeven_figure.y_scale = "log";
    report.add_figure(std::move(oddeven_figure));
    report.add_picture({"velocity_y_ramp", run_directory.string(), "velocity", 1, 0.1, 0.0,
                        "v_y at t = 0.1 s, half-way through the gravity ramp (the top is clamped; "
                        "the free end at the bottom moves fastest)."});
    report.add_picture({"velocity_y_end", run_directory.string(), "velocity", 1, -1.0, 0.0,
                        "v_y at the end: what is left after the damping."});
  }
  // tip 2 %: the lattice and the clamp's restraint of the lateral contraction at the top.
  return {
      check_at_most("hourglass_velocity_ratio", ratio, 0.0, 1e-3, "fraction"),
      check_at_most("tip_displacement_error", tip_error, 0.0, 0.02, "fraction"),
  };
}

}  // namespace rktsph::case_checks::hanging_beam
