// Thesis §6.4.4 (docs/theory.md §8.10): a flexible strip load applied
// quickly to a nearly undrained elastic stratum; half model with the symmetry plane x = 0.
// Checks, both on the last state (load held, shear ringing damped, t << b^2/c_v):
//   centreline_pressure_error  max over z/b = 0.5, 1, 2 of |p_w/p0 - 1| on the centre line, with
//                              p0 = F (2q/pi) atan(b/z) the undrained half-plane value and
//                              F = B(1+nu_u)2/3 its compressible-fluid factor (0.9987 here). The
//                              box walls change p0 by at most 1.8 % at these depths (README.md).
//   checkerboard_ratio         largest node-to-node alternating component of p_w over max |p_w|;
//                              see checkerboard_amplitude() for why a 3x3 stencil and which nodes.
//   residual_velocity_ratio    largest |v| over all nodes at the end over its peak during the run
//                              (rest_checks.hpp): the damped body must come to rest.
//   settlement_oddeven_ratio   the odd-even part of the surface settlement over 0 <= x <= 5b
//                              over its largest value (rest_checks.hpp).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "rktsph/core/error.hpp"
#include "rktsph/validation/references/limit_loads.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::vpw_strip_footing_elastic {

namespace {

constexpr double kDepthsOverHalfWidth[] = {0.5, 1.0, 2.0};
// No separate quick variant: the full run takes about 25 s, and coarser or shorter runs do not
// resolve the edge of the load for the 10 % and 1 % tolerances (centre-line error and checkerboard
// ratio 0.27 / 0.013 at b/dx = 4, 0.100 / 0.011 at b/dx = 6, 0.099 / 0.005 at b/dx = 8 stopped at
// 2.5 s while the loading still rings).

LatticeField pore_pressure_on_lattice(const Simulation& simulation) {
  return lattice_field(simulation, simulation.model().pore_pressure_field());
}

double centre_line_value(const LatticeField& field, const StripLoad& strip, double depth) {
  const int i = static_cast<int>(std::lround(-field.origin_x / field.spacing));
  const int j =
      static_cast<int>(std::lround((strip.row.surface - depth - field.origin_y) / field.spacing));
  return field.at(i, j);
}

// The (-1)^(i+j) component of p_w (checkerboard_amplitude, validation/rest_checks.hpp: the 3x3
// stencil, which returns 0 on the drained-surface boundary layer that varies in y only). The
// undrained field is singular at the footing edge itself, so nodes within max(b/2, 3 dx) of it are
// left out (docs/theory.md §8.10 excludes the same zone for p), and so are nodes without a full
// 3x3 neighbourhood.
double pore_pressure_checkerboard(const LatticeField& field, const StripLoad& strip) {
  const double exclusion = std::max(0.5 * strip.half_width, 3.0 * field.spacing);
  return checkerboard_amplitude(field, [exclusion, &strip](double x, double y) {
    return std::hypot(x - strip.half_width, y - strip.row.surface) < exclusion;
  });
}

/// Centre-line p_w against depth and the histories at z = b and 2b, each against the undrained
/// half-plane value, and a picture of p_w.
void report_strip_footing(ValidationReport& report, const StripLoad& strip,
                          const std::filesystem::path& run_directory, const LatticeField& field,
                          double factor, double centre_line_error, double checkerboard) {
  const double q = strip.pressure, b = strip.half_width, surface = strip.row.surface;
  const auto reference = [factor, b](double load, double depth) {
    return factor * references::strip_centre_line_pore_pressure(load, b, depth);
  };
  // Every node of the centre line x = 0, from the surface down.
  Series centre_line{"SPH, centre-line nodes", {}, {}, "points"};
  const int column = static_cast<int>(std::lround(-field.origin_x / field.spacing));
  for (int j = field.rows - 1; j >= 0; --j) {
    const double value = field.at(column, j);
    if (std::isnan(value)) continue;
    centre_line.x.push_back(surface - (field.origin_y + j * field.spacing));
    centre_line.y.push_back(1e-3 * value);
  }
  Series checked{"SPH at the checked depths z/b = 0.5, 1, 2", {}, {}, "points"};
  std::string errors;
  for (double depth_ratio : kDepthsOverHalfWidth) {
    const double depth = depth_ratio * b;
    const double value = centre_line_value(field, strip, depth);
    checked.x.push_back(depth);
    checked.y.push_back(1e-3 * value);
    errors += fmt::format("{}{:.1f} % at z/b = {:g}", errors.empty() ? "" : ", ",
                          100.0 * relative_error(value, reference(q, depth)), depth_ratio);
  }
  const double bottom = centre_line.x.empty() ? surface : centre_line.x.back();
  report.add_figure({"centreline_pressure",
                     "Pore pressure on the centre line under the strip load, end of the run",
                     "depth below the loaded surface z [m]",
                     "excess pore pressure p_w [kPa]",
                     {std::move(centre_line), std::move(checked),
                      sample_curve("undrained half-plane F (2q/pi) atan(b/z)", 0.0, bottom, 2000,
                                   [&](double depth) { return 1e-3 * reference(q, depth); })}});

  const ProbeTable probes = ProbeTable::read(run_directory / "probes.csv");
  const TimeFunction* traction = strip.history;
  const double end = probes.time().back();
  Figure histories{"probe_pressure",
                   "Pore pressure on the centre line at z = b and z = 2b",
                   "time [s]",
                   "excess pore pressure p_w [kPa]",
                   {}};
  const std::pair<const char*, double> stations[] = {{"b.pore_pressure", 1.0},
                                                     {"twob.pore_pressure", 2.0}};
  for (const auto& [column_name, depth_ratio] : stations) {
    Series measured{fmt::format("SPH, z = {:g} b", depth_ratio), probes.time(),
                    probes.column(column_name), "line"};
    for (double& p : measured.y)
      p *= 1e-3;
    histories.series.push_back(std::move(measured));
    // An init-capture: clang 14 cannot capture a structured binding (C++20 allows it).
    if (traction)
      histories.series.push_back(
          sample_curve(fmt::format("undrained, z = {:g} b, under the applied q(t)", depth_ratio),
                       0.0, end, 2000, [&, depth = depth_ratio](double t) {
                         return 1e-3 * reference(-(*traction)(t), depth * b);
                       }));
  }
  report.add_figure(std::move(histories));

  report.describe(fmt::format(
      "Thesis 6.4.4: a flexible strip load q = {:g} kPa, b = {:g} m, ramped in over the first "
      "{:g} s onto a nearly undrained saturated elastic stratum (half model, symmetry plane x = "
      "0, dx = {:g} m, drained surface, mass damping to remove the ringing); the state is read at "
      "the end. Reference: the undrained half-plane pore pressure on the centre line, p0 = F "
      "(2q/pi) atan(b/z), F = {:.4f} the compressible-fluid factor. Measured error against it: "
      "{} (largest {:.1f} %); checkerboard ratio {:.4f}. The centre-line check is a known open "
      "problem.",
      1e-3 * q, b, traction ? traction->duration : 0.0, field.spacing, factor, errors,
      100.0 * centre_line_error, checkerboard));
  double largest = 0.0, largest_x = 0.0, largest_depth = 0.0;
  for (int j = 0; j < field.rows; ++j)
    for (int i = 0; i < field.columns; ++i)
      if (const double value = field.at(i, j);
          !std::isnan(value) && std::abs(value) > std::abs(largest)) {
        largest = value;
        largest_x = field.origin_x + i * field.spacing;
        largest_depth = surface - (field.origin_y + j * field.spacing);
      }
  report.add_picture(
      {"pore_pressure", run_directory.string(), "pore_pressure", -1, -1.0, 0.0,
       fmt::format("Excess pore pressure at the end of the run; the strip load covers 0 < x < b = "
                   "{:g} m at the top left, the surface is drained. Largest |p_w|: {:.0f} kPa "
                   "({:.1f} q) at the node x = {:g} m, z = {:g} m.",
                   b, 1e-3 * largest, std::abs(largest) / q, largest_x, largest_depth)});
}

}  // namespace

std::vector<CheckResult> validate_vpw_strip_footing_elastic(const ValidationContext& context) {
  std::vector<CaseOverride> overrides = {{"output.interval", "0"}};
  const CaseDescription description =
      load_bundled_case(context, "vpw-strip-footing-elastic", overrides);
  const StripLoad strip = read_strip_load(description);
  if (!description.pore_fluid) throw RunError("case vpw-strip-footing-elastic: no pore_fluid");
  const double factor = references::strip_undrained_compressibility_factor(
      material_parameter(description, "soil", "young_modulus"),
      material_parameter(description, "soil", "poisson_ratio"), description.pore_fluid->porosity,
      description.pore_fluid->bulk_modulus);
  LatticeField field;
  NodeLine settlement;
  SpeedRecorder speeds(description.output.probe_interval);
  const std::filesystem::path run_directory = run_for_validation(
      context, description, "full",
      [&](const Simulation& simulation) {
        field = pore_pressure_on_lattice(simulation);
        settlement = surface_settlement(simulation, strip.row.surface, 0.0, strip.row.body.x_max);
      },
      {&speeds.observer()});

  double centre_line_error = 0.0;
  for (double depth_ratio : kDepthsOverHalfWidth) {
    const double depth = depth_ratio * strip.half_width;
    const double reference = factor * references::strip_centre_line_pore_pressure(
                                          strip.pressure, strip.half_width, depth);
    centre_line_error = std::max(centre_line_error,
                                 relative_error(centre_line_value(field, strip, depth), reference));
  }
  const double checkerboard = pore_pressure_checkerboard(field, strip) / max_abs(field);
  const double residual = residual_velocity_ratio(speeds.history());
  const double settlement_ratio = settlement_oddeven_ratio(settlement, strip.half_width);
  if (context.report) {
    report_strip_footing(*context.report, strip, run_directory, field, factor, centre_line_error,
                         checkerboard);
    context.report->add_figure(settlement_figure(
        "surface_settlement", settlement, strip.half_width,
        fmt::format("Surface settlement at the end (odd-even ratio over 0 <= x <= 5b: {:.4f})",
                    settlement_ratio)));
    context.report->add_figure(speed_figure("max_velocity", speeds.history(), 0.0, 1e-3));
    context.report->add_picture(
        {"velocity", run_directory.string(), "velocity", -1, -1.0, 0.0,
         fmt::format("Velocity magnitude at the end (load held after its ramp, damped): largest "
                     "{:.3g} m/s, {:.2g} of its peak during the run.",
                     speeds.history().speed.back(), residual)});
  }
  // 10 %: the box walls account for up to 1.8 %, the drained-surface boundary layer of the
  // projection (one to two nodes, docs/theory.md §7.2, S7) reaches z = b/2 only at
  // b/dx = 4, and the nodal load edge is resolved to dx/2.
  // residual_velocity_ratio: a damped elastic body under a held load comes to rest (t << b^2/c_v:
  // no consolidation over the run); settlement_oddeven_ratio: the exact profile gives about 0.007
  // at b = 8 dx (its kink at the load edge), an odd-even pattern its full amplitude.
  return {
      check_at_most("centreline_pressure_error", centre_line_error, 0.0, 0.10, "fraction"),
      check_at_most("checkerboard_ratio", checkerboard, 0.0, 0.01, "fraction"),
      check_at_most("residual_velocity_ratio", residual, 0.0, 1e-3, "fraction"),
      check_at_most("settlement_oddeven_ratio", settlement_ratio, 0.0, 0.03, "fraction"),
  };
}

}  // namespace rktsph::case_checks::vpw_strip_footing_elastic
