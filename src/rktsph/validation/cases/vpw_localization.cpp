// Thesis §6.4.5 (validation.md §6.4.5): strain localisation in a saturated sample. The sample,
// material and loading of §4.4 (cases/sample2d-localization) with pore water, low permeability and
// drained faces. Von Mises flow on the effective stress is isochoric, so the nearly undrained
// sample localises like the dry one. Checks:
//   shear_band_angle   acute angle between the band and the loading (vertical) axis, measured
//                      from the eps_vp field at the end (validation/band_angle.hpp); 45° ± 3°.
//   band_distance_to_weak_zone  the band must start from the imperfection (weak-zone
//                      half-diagonal plus one spacing).
// The pore-pressure change inside the band (mean p_w of the band strip minus that of the quiet
// upper part, at the end) is written to the report description; it is a result, not a check.
#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include <fmt/format.h>

#include "rktsph/core/error.hpp"
#include "rktsph/validation/band_angle.hpp"
#include "rktsph/validation/references/limit_loads.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph {

namespace {
constexpr double kQuickSpacing = 0.05;    // 21 x 41 nodes, as the dry quick variant
constexpr double kWeakZoneCentre = 0.05;  // the weak zone is [0, 0.1] x [0, 0.1]
constexpr double kWeakZoneHalfDiagonal = 0.0707;

}  // namespace

std::vector<CheckResult> validate_vpw_localization(const ValidationContext& context) {
  std::vector<CaseOverride> overrides;
  if (context.quick) overrides.push_back({"geometry.spacing", std::to_string(kQuickSpacing)});
  const CaseDescription description = load_bundled_case(context, "vpw-localization", overrides);

  std::optional<BandMeasurement> band;
  const auto measure_final_band = [&](const Simulation& simulation) {
    const auto& names = simulation.model().internal_names();
    const auto field = std::find(names.begin(), names.end(), "eps_vp");
    if (field == names.end()) throw RunError("vpw-localization: the model has no eps_vp");
    const PointCloud& nodes = simulation.nodes().sph_nodes;
    const double* strain =
        simulation.state().internal.field(static_cast<int>(field - names.begin()));
    band = measure_band(nodes.position[0], nodes.position[1],
                        std::span<const double>(strain, nodes.size()), BandAngleOptions{});
  };
  const auto directory = run_for_validation(context, description, context.quick ? "quick" : "full",
                                            measure_final_band);
  if (!band) throw RunError("vpw-localization: the band was not measured");

  if (context.report) {
    const ProbeTable probes = ProbeTable::read(directory / "probes.csv");
    const double end = probes.time().back();
    const double change =
        probes.mean("band.pore_pressure", end, end) - probes.mean("quiet.pore_pressure", end, end);
    context.report->describe(fmt::format(
        "Saturated sample (k = 1e-6 m/s) in plane-strain compression; band at {:.1f} deg. Pore "
        "pressure in the band minus above it at the end: {:.1f} kPa.",
        band->primary.angle_deg, change / 1000.0));
  }
  return {
      check_within("shear_band_angle", band->primary.angle_deg,
                   references::j2_plane_strain_band_angle_deg(), 3.0, "deg"),
      check_at_most("band_distance_to_weak_zone",
                    distance_to_band(band->primary, kWeakZoneCentre, kWeakZoneCentre), 0.0,
                    kWeakZoneHalfDiagonal + description.geometry.spacing, "m"),
  };
}

}  // namespace rktsph
