// Thesis §5.3.7 and Appendix 5 (docs/theory.md §8.7, §9.12): a smooth rigid strip footing of width
// B pushed at a constant velocity into a deep, weightless Von Mises–Perzyna stratum with the
// large-deformation model (half model about x = 0). Checks:
//   bearing_capacity_error  q0/((2 + pi) c) - 1, q0 the small-deformation bearing capacity the
//                           run implies: the footing pressure q(s) (the mean of the footing's
//                           vertical stress, trapezoidal weights over its nodes, the node on the
//                           symmetry plane and the edge node counting half) is fitted by a straight
//                           line over the settlements 0.1 B <= s <= 0.2 B and q0 is its value at
//                           s = 0. A footing that penetrates a weightless Tresca soil does not keep
//                           a plateau: the heave and the embedment raise its resistance with s
//                           (docs/theory.md §9.12), to first order linearly, so the plateau of
//                           Prandtl's rigid-plastic analysis is that line's intercept. Within
//                           -3 %/+5 % (the reference column holds the middle of that band, 0.01,
//                           the tolerance its half width, 0.04). The Perzyna overstress is below
//                           1 %: V/(gamma B) = 0.005. A run that stops before 0.2 B has no
//                           line: the check then fails with no value (null in the JSON line).
//   settlement_reached      the footing's settlement at the end over B (>= 0.2).
//   contact_pressure_oddeven_ratio  the odd-even part of the node-by-node contact pressure on the
//                           interior footing nodes over its mean (rest_checks.hpp), the largest
//                           over the states sampled every second on the plateau.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "rktsph/core/error.hpp"
#include "rktsph/validation/references/limit_loads.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::ld_strip_footing_bearing {

namespace {

constexpr char kCase[] = "ld-strip-footing-bearing";
constexpr double kPlateauFrom = 0.1, kPlateauTo = 0.2;  // settlement over B
constexpr double kSampling = 1.0;                       // [s] of simulated time
constexpr double kQuickSpacing = 0.25;                  // B/dx = 16 instead of 32

/// The least-squares line q = intercept + slope s/B through the pressure over the plateau window.
struct PressureLine {
  double intercept = 0.0, slope = 0.0;
};

// The line, or nothing when the run did not settle through the window (it stopped early).
std::optional<PressureLine> fit_plateau(const FootingHistory& history, double footing_width) {
  double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (std::size_t row = 0; row < history.pressure.size(); ++row) {
    const double s = history.settlement[row] / footing_width;
    if (s < kPlateauFrom || s > kPlateauTo) continue;
    n += 1.0;
    sx += s;
    sy += history.pressure[row];
    sxx += s * s;
    sxy += s * history.pressure[row];
  }
  const double spread = n * sxx - sx * sx;
  if (n < 2.0 || spread <= 0.0) return std::nullopt;
  const double slope = (n * sxy - sx * sy) / spread;
  return PressureLine{(sy - slope * sx) / n, slope};
}

void report_bearing(ValidationReport& report, const ValidationRun& run, double footing_width,
                    const FootingHistory& history, const FootingHistory* coarse, double spacing,
                    double capacity, const std::optional<PressureLine>& line,
                    const NodeLine& contact, double contact_ratio) {
  const std::string fitted =
      line ? fmt::format(
                 "the line fitted to the pressure over {:g} B <= s <= {:g} B gives q = "
                 "{:.1f} kPa + {:.1f} kPa x s/B, and its intercept is the checked bearing "
                 "capacity.",
                 kPlateauFrom, kPlateauTo, 1e-3 * line->intercept, 1e-3 * line->slope)
           : fmt::format(
                 "the run did not settle through {:g} B <= s <= {:g} B, so no line is "
                 "fitted and the bearing capacity is not measured.",
                 kPlateauFrom, kPlateauTo);
  report.describe(
      fmt::format("Thesis 5.3.7 (Appendix 5): a smooth rigid strip footing B = {:g} m (half "
                  "model, dx = {:g} m) pushed at a constant rate into a deep, weightless Von "
                  "Mises-Perzyna stratum to a settlement of {:.2f} B with the large-deformation "
                  "model. Reference: Prandtl's bearing capacity (2 + pi) c = {:.1f} kPa. A "
                  "penetrating footing gains resistance with its settlement s (heave and "
                  "embedment); {}",
                  footing_width, spacing, history.settlement.back() / footing_width,
                  1e-3 * capacity, fitted) +
      (run.completed ? std::string() : " The run stopped early: " + run.message));
  const double end = history.settlement.back() / footing_width;
  Figure load{
      "load_settlement",
      "Footing pressure against settlement (as thesis Fig. 5-54)",
      "settlement s / B [-]",
      "footing pressure q [kPa]",
      {footing_pressure_series(fmt::format("SPH, dx = {:g} m", spacing), history, footing_width)}};
  if (coarse)
    load.series.push_back(
        footing_pressure_series(fmt::format("SPH, dx = {:g} m (to s = {:.2f} B)", kQuickSpacing,
                                            coarse->settlement.back() / footing_width),
                                *coarse, footing_width));
  load.series.push_back(
      sample_curve("(2 + pi) c", 0.0, end, 2, [&](double) { return 1e-3 * capacity; }));
  if (line)
    load.series.push_back(sample_curve(
        "line fitted over the window", 0.0, end, 2,
        [&](double s) { return 1e-3 * (line->intercept + line->slope * s); }, "line"));
  load.series.push_back(
      sample_curve("+5 % / -3 %", 0.0, end, 2, [&](double) { return 1.05e-3 * capacity; }));
  load.series.push_back(sample_curve("", 0.0, end, 2, [&](double) { return 0.97e-3 * capacity; }));
  report.add_figure(std::move(load));
  Series pressure{"SPH footing nodes", contact.x, {}, "line"};
  for (double p : contact.value)
    pressure.y.push_back(1e-3 * p);
  report.add_figure(
      {"contact_pressure",
       fmt::format("Contact pressure node by node at the end of the plateau (odd-even ratio, "
                   "largest on the plateau: {:.4f})",
                   contact_ratio),
       fmt::format("x of the node in the reference configuration [m] (footing 0 <= x <= {:g} m)",
                   0.5 * footing_width),
       "-sigma_yy [kPa]",
       {std::move(pressure), sample_curve("(2 + pi) c", 0.0, 0.5 * footing_width, 2,
                                          [&](double) { return 1e-3 * capacity; })}});
  report.add_picture({"eps_vp", run.directory.string(), "eps_vp", -1, -1.0, 1.0,
                      "Equivalent viscoplastic strain at the end of the push on the deformed "
                      "configuration (true scale): the Prandtl mechanism, with the heave beside "
                      "the footing."});
}

}  // namespace

std::vector<CheckResult> validate_ld_strip_footing_bearing(const ValidationContext& context) {
  // The half model: the footing from the symmetry plane x = 0 to its edge at B/2.
  const HalfModelFooting half_model = half_model_footing(context, kCase, kQuickSpacing);
  const CaseDescription& description = half_model.description;
  const FootingRow& footing = half_model.row;
  const double spacing = description.geometry.spacing;
  const double half_width = footing.right, footing_width = half_model.width;
  const int footing_nodes = half_model.nodes;

  FootingContactSampler contact{footing.surface, 0.0,          half_width,
                                footing_width,   kPlateauFrom, kPlateauTo};
  SampledObserver plateau_states(kSampling,
                                 [&](const Simulation& simulation) { contact.sample(simulation); });
  // A run that stops early (a cell folding at the footing's edge, docs/theory.md §9.12) is checked
  // on what it wrote: settlement_reached then fails with the settlement it got to.
  const ValidationRun run = run_allowing_failure(
      context, description, context.quick ? "quick" : "full", {}, {&plateau_states});
  const std::filesystem::path& directory = run.directory;
  const FootingHistory history =
      read_footing_history(directory, footing_nodes, "stress_yy", "edge", "centre");
  const double capacity =
      references::prandtl_bearing_capacity(references::von_mises_plane_strain_cohesion(
          material_parameter(description, "soil", "yield_stress")));
  const std::optional<PressureLine> line = fit_plateau(history, footing_width);
  if (context.report) {
    // The second resolution of the report (full runs only): the quick variant's lattice.
    std::optional<FootingHistory> coarse;
    if (!context.quick)
      coarse = run_coarse_footing(context, kCase, kQuickSpacing, half_width, "stress_yy", "edge",
                                  "centre");
    report_bearing(*context.report, run, footing_width, history, coarse ? &*coarse : nullptr,
                   spacing, capacity, line, contact.last, contact.largest_ratio);
  }
  // bearing_capacity_error: +5 %/-3 % as the issue asks, after the rate correction (the
  // overstress is below 1 % here). contact_pressure_oddeven_ratio 5 % as the vertical cut.
  return {
      // Not measured (NaN, a failed check) when the run stopped before 0.2 B.
      check_within("bearing_capacity_error", line ? line->intercept / capacity - 1.0 : std::nan(""),
                   0.01, 0.04, "fraction"),
      check_at_least("settlement_reached", history.settlement.back() / footing_width, 0.2, 0.2,
                     "fraction"),
      check_at_most("contact_pressure_oddeven_ratio", contact.largest_ratio, 0.0, 0.05, "fraction"),
  };
}

}  // namespace rktsph::case_checks::ld_strip_footing_bearing
