// Thesis §6.4.5 (docs/theory.md §8.4): strain localisation in a saturated sample. The sample,
// material and loading of thesis §4.4 (cases/sample2d-localization) with pore water, low
// permeability and drained faces. Von Mises flow on the effective stress is isochoric, so the
// nearly undrained sample localises like the dry one. Checks:
//   shear_band_angle   acute angle between the band and the loading (vertical) axis, measured
//                      from the eps_vp field at the end (validation/band_angle.hpp); 45° ± 3°.
//   band_distance_to_weak_zone  the band must start from the imperfection (weak-zone
//                      half-diagonal plus one spacing).
// The pore-pressure change inside the band (mean p_w of the band strip minus that of the quiet
// upper part, at the end) is written to the report description; it is a result, not a check.
// The report also draws the band's centre line (row by row and as fitted) against the 45° line
// through the weak zone, p_w in and out of the band, and pictures of eps_vp and p_w.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "rktsph/core/error.hpp"
#include "rktsph/validation/band_angle.hpp"
#include "rktsph/validation/references/limit_loads.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::vpw_localization {

namespace {
constexpr double kQuickSpacing = 0.05;  // 21 x 41 nodes, as the dry quick variant
// The lattice rows whose band centre the report draws: between the weak zone and where the band
// leaves the right side [m].
constexpr double kRidgeLow = 0.15, kRidgeHigh = 0.85;

/// The band's centre line against the 45-degree line from the weak zone, p_w in and out of the
/// band against time, and pictures of eps_vp and p_w.
void report_localization(ValidationReport& report, const std::filesystem::path& run_directory,
                         const WeakZone& weak, const BandMeasurement& band,
                         const std::vector<std::pair<double, double>>& centres,
                         const std::array<double, 3>& largest_pressure, double spacing) {
  const double reference_angle = references::j2_plane_strain_band_angle_deg();
  report.add_figure(
      {"band_fit",
       "Shear band at the end of the run: centre line against the reference",
       "x [m]",
       "y [m] (axes not to scale)",
       {band_centre_series(centres), band_ridge_series(band.primary, kRidgeLow, kRidgeHigh),
        line_from_vertical(
            fmt::format("{:g} degrees from the vertical through the weak zone centre",
                        reference_angle),
            weak.centre_x(), weak.centre_y(), reference_angle, kRidgeLow, kRidgeHigh, "dashed")}});

  const ProbeTable probes = ProbeTable::read(run_directory / "probes.csv");
  const double end = probes.time().back();
  const double change =
      probes.mean("band.pore_pressure", end, end) - probes.mean("quiet.pore_pressure", end, end);
  Series in_band{"mean in the band strip (45-degree strip from the weak zone)", probes.time(),
                 probes.column("band.pore_pressure"), "line"};
  Series quiet{"mean in the quiet upper part (y > 1.3 m)", probes.time(),
               probes.column("quiet.pore_pressure"), "line"};
  for (Series* series : {&in_band, &quiet})
    for (double& p : series->y)
      p *= 1e-3;
  report.add_figure({"pore_pressure_band",
                     "Excess pore pressure in and out of the band",
                     "time [s]",
                     "excess pore pressure p_w [kPa]",
                     {std::move(in_band), std::move(quiet)}});

  report.describe(fmt::format(
      "Thesis 6.4.5: the plane-strain compression sample of 4.4 (dx = {:g} m, "
      "softening Von Mises-Perzyna on the effective stress, weak zone in the lower left corner) "
      "saturated, with a low permeability and drained faces: nearly undrained over the run. "
      "Undrained "
      "J2 flow is isochoric, so the band should run at {:g} degrees from the loading axis, "
      "starting from the weak zone. Measured band (ridge fit of eps_vp at the end): {:.1f} "
      "degrees, {:.3f} m from the weak zone centre. Pore pressure in the band minus above it "
      "at the end: {:.1f} kPa (a result, not a check).",
      spacing, reference_angle, band.primary.angle_deg,
      distance_to_band(band.primary, weak.centre_x(), weak.centre_y()), change / 1000.0));
  report.add_picture({"eps_vp", run_directory.string(), "eps_vp", -1, -1.0, 0.0,
                      "Equivalent viscoplastic strain at the end: the shear band from the weak "
                      "corner (lower left) across the sample."});
  report.add_picture(
      {"pore_pressure", run_directory.string(), "pore_pressure", -1, -1.0, 0.0,
       fmt::format("Excess pore pressure at the end (drained sides and top: p_w = 0 there). "
                   "Largest |p_w|: {:.0f} kPa at the node (x, y) = ({:g}, {:g}) m.",
                   1e-3 * largest_pressure[0], largest_pressure[1], largest_pressure[2])});
}

}  // namespace

std::vector<CheckResult> validate_vpw_localization(const ValidationContext& context) {
  std::vector<CaseOverride> overrides;
  if (context.quick) overrides.push_back({"geometry.spacing", std::to_string(kQuickSpacing)});
  const CaseDescription description = load_bundled_case(context, "vpw-localization", overrides);
  const WeakZone weak = read_weak_zone(description);

  std::optional<BandMeasurement> band;
  std::vector<std::pair<double, double>> centres;
  std::array<double, 3> largest_pressure{};  // p_w, x, y of the largest |p_w| at the end
  const auto measure_final_band = [&](const Simulation& simulation) {
    const PointCloud& nodes = simulation.nodes().sph_nodes;
    const std::span<const double> strain =
        internal_variable(simulation, "eps_vp", "vpw-localization");
    band = measure_band(nodes.position[0], nodes.position[1], strain, BandAngleOptions{});
    if (context.report) {
      centres =
          band_row_centres(simulation.nodes(), strain, band->threshold, kRidgeLow, kRidgeHigh);
      const int pore = simulation.model().pore_pressure_field();
      for (std::size_t k = 0; k < nodes.size(); ++k)
        if (const double value = simulation.state().fields(pore, k);
            std::abs(value) > std::abs(largest_pressure[0]))
          largest_pressure = {value, nodes.position[0][k], nodes.position[1][k]};
    }
  };
  const auto directory = run_for_validation(context, description, context.quick ? "quick" : "full",
                                            measure_final_band);
  if (!band) throw RunError("vpw-localization: the band was not measured");

  if (context.report)
    report_localization(*context.report, directory, weak, *band, centres, largest_pressure,
                        description.geometry.spacing);
  return {
      check_within("shear_band_angle", band->primary.angle_deg,
                   references::j2_plane_strain_band_angle_deg(), 3.0, "deg"),
      check_at_most("band_distance_to_weak_zone",
                    distance_to_band(band->primary, weak.centre_x(), weak.centre_y()), 0.0,
                    weak.half_diagonal() + description.geometry.spacing, "m"),
  };
}

}  // namespace rktsph::case_checks::vpw_localization
