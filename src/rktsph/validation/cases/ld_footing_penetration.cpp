// Issue 29 (docs/theory.md §9.12, §9.16): the undrained rigid strip footing pushed to a settlement
// of one width B into weightless Tresca soil, in the set-up of the large-deformation finite-element
// study of Kardani et al. (2015) (B = 1 m, soil 10 B x 5 B, E = 100 kPa, nu = 0.495, s_u = 1 kPa),
// half model about x = 0. Checks:
//   capacity_at_0.1B_error  q/((2 + pi) s_u) - 1 at the settlement s = 0.1 B, q the footing
//                           pressure (the mean of the footing's vertical stress, trapezoidal
//                           weights over its nodes, the node on the symmetry plane and the edge
//                           node counting half), linear between the probe rows around 0.1 B. At
//                           0.1 B the heave and embedment have raised Prandtl's rigid-plastic value
//                           by a few per cent in the large-deformation analyses, and a locking
//                           discretisation of nu = 0.495 gives no value near it. Within
//                           -3 %/+10 % (the reference column holds the middle of that band, 0.035,
//                           the tolerance its half width, 0.065). The Perzyna overstress is below
//                           1 %: V/(gamma B) = 0.005. A run that stops before 0.1 B has no value.
//   settlement_reached      the footing's settlement at the end over B (>= 1).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "rktsph/validation/references/limit_loads.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::ld_footing_penetration {

namespace {

constexpr char kCase[] = "ld-footing-penetration";
constexpr double kCapacitySettlement = 0.1;  // over B
constexpr double kQuickSpacing = 0.125;      // B/dx = 8 instead of 16

// The pressure at the settlement s (over B), linear between the first two rows around it;
// nothing when the run did not settle that far.
std::optional<double> pressure_at(const FootingHistory& history, double footing_width, double s) {
  for (std::size_t row = 1; row < history.settlement.size(); ++row) {
    const double before = history.settlement[row - 1] / footing_width;
    const double after = history.settlement[row] / footing_width;
    if (before <= s && s <= after && after > before)
      return history.pressure[row - 1] +
             (history.pressure[row] - history.pressure[row - 1]) * (s - before) / (after - before);
  }
  return std::nullopt;
}

void report_penetration(ValidationReport& report, const ValidationRun& run,
                        const FootingHistory& history, double footing_width, double spacing,
                        double shear_strength, const std::optional<double>& capacity) {
  const double reached = history.settlement.back() / footing_width;
  report.describe(
      fmt::format(
          "The undrained rigid strip footing of Kardani et al. (2015) (B = {:g} m, half model, "
          "dx = {:g} m, weightless Tresca soil, E = 100 kPa, nu = 0.495, s_u = {:g} kPa) pushed "
          "at a constant rate to {:.2f} B with the large-deformation model. Reference: "
          "Prandtl's (2 + pi) s_u at small settlement, and a resistance that rises with "
          "penetration in the large-deformation analyses. At 0.1 B, q/s_u = {}.",
          footing_width, spacing, 1e-3 * shear_strength, reached,
          capacity ? fmt::format("{:.3f}", *capacity / shear_strength) : "not reached") +
      (run.completed ? std::string() : " The run stopped early: " + run.message));
  Series measured{fmt::format("SPH, dx = {:g} m", spacing), {}, {}, "line"};
  for (std::size_t row = 0; row < history.pressure.size(); ++row) {
    measured.x.push_back(history.settlement[row] / footing_width);
    measured.y.push_back(history.pressure[row] / shear_strength);
  }
  const double end = std::max(1.0, reached);
  report.add_figure(
      {"resistance",
       "Normalised footing resistance against penetration",
       "settlement s / B [-]",
       "q / s_u [-]",
       {std::move(measured),
        sample_curve("2 + pi (Prandtl)", 0.0, end, 2,
                     [](double) { return 2.0 + std::numbers::pi; }),
        sample_curve("-3 % / +10 % at 0.1 B", 0.05, 0.15, 2,
                     [](double) { return 1.10 * (2.0 + std::numbers::pi); }),
        sample_curve("", 0.05, 0.15, 2, [](double) { return 0.97 * (2.0 + std::numbers::pi); })}});
  report.add_picture({"eps_vp", run.directory.string(), "eps_vp", -1, -1.0, 1.0,
                      "Equivalent viscoplastic strain at the end of the push on the deformed "
                      "configuration (true scale)."});
}

}  // namespace

std::vector<CheckResult> validate_ld_footing_penetration(const ValidationContext& context) {
  const HalfModelFooting footing = half_model_footing(context, kCase, kQuickSpacing);
  const CaseDescription& description = footing.description;
  const double spacing = description.geometry.spacing, footing_width = footing.width;
  // A run that stops early (a cell folding beside the footing's edge, docs/theory.md §9.12) is
  // checked on what it wrote: settlement_reached then fails with the settlement it got to.
  const ValidationRun run =
      run_allowing_failure(context, description, context.quick ? "quick" : "full");
  const FootingHistory history =
      read_footing_history(run.directory, footing.nodes, "stress_yy", "edge", "centre");
  const double shear_strength = references::von_mises_plane_strain_cohesion(
      material_parameter(description, "clay", "yield_stress"));
  const double prandtl = references::prandtl_bearing_capacity(shear_strength);
  const std::optional<double> capacity = pressure_at(history, footing_width, kCapacitySettlement);
  if (context.report)
    report_penetration(*context.report, run, history, footing_width, spacing, shear_strength,
                       capacity);
  return {
      // Not measured (NaN, a failed check) when the run stopped before 0.1 B.
      check_within("capacity_at_0.1B_error", capacity ? *capacity / prandtl - 1.0 : std::nan(""),
                   0.035, 0.065, "fraction"),
      check_at_least("settlement_reached", history.settlement.back() / footing_width, 1.0, 1.0,
                     "fraction"),
  };
}

}  // namespace rktsph::case_checks::ld_footing_penetration
