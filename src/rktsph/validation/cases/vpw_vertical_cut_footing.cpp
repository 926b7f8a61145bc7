// Thesis §6.4.6 (validation.md §6.4.6 and §5.3.6): a smooth rigid strip footing of width B flush
// with the crest of a vertical cut in saturated, weightless Von Mises–Perzyna soil (plasticity on
// the effective stress), pushed down at a constant velocity with a low permeability (undrained).
// Checks:
//   limit_pressure_error  |q/(2c) - 1| with q the footing pressure on the plateau: the mean total
//                         vertical stress under the footing (trapezoidal weights over its nodes,
//                         from probes.csv) over the last fifth of the run, and c = Y/sqrt(3)
//                         (validation.md §5.3.6: the uniaxial column under the footing and the 45°
//                         wedge from its inner edge to the face both give 2c, drained or
//                         undrained). The Perzyna overstress is kept below 1 %: V/(gamma B) = 0.004
//                         (§0).
//   shear_band_angle      the band of eps_vp at the end (validation/band_angle.hpp), measured from
//                         the vertical: 45° ± 5° (§5.3.6).
#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include "rktsph/core/error.hpp"
#include "rktsph/validation/band_angle.hpp"
#include "rktsph/validation/references/limit_loads.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph {

namespace {

// As in cases/vpw-vertical-cut-footing/case.yaml.
constexpr double kYieldStress = 1.0e5;
constexpr double kFootingWidth = 2.0;
constexpr double kFootingLeft = 6.0;  // inner footing edge; the crest is at x = 8 m, y = 6 m
constexpr double kCrestY = 6.0;
// The band is measured in the region the 45° wedge can reach: below the footing and up to 2B
// under the crest, which leaves out the far field where eps_vp stays zero.
constexpr double kBandRegionDepth = 2.0 * kFootingWidth;
// Quick variant: B/dx = 8 instead of 16 (at B/dx = 4 the band measures 61°, not resolved).
constexpr double kQuickSpacing = 0.25;

// Mean over the footing nodes with trapezoidal weights (the two end nodes count half), from the
// group mean of the probe and the two end-node probes.
double footing_pressure(const ProbeTable& probes, std::size_t row, int node_count) {
  const double sum = probes.column("footing.total_stress_yy")[row] * node_count;
  const double ends =
      probes.column("inner.total_stress_yy")[row] + probes.column("crest.total_stress_yy")[row];
  return -(sum - 0.5 * ends) / (node_count - 1);
}

BandMeasurement measure_wedge_band(const Simulation& simulation) {
  const auto& names = simulation.model().internal_names();
  const auto field = std::find(names.begin(), names.end(), "eps_vp");
  if (field == names.end()) throw RunError("vpw-vertical-cut-footing: the model has no eps_vp");
  const PointCloud& nodes = simulation.nodes().sph_nodes;
  const double* strain = simulation.state().internal.field(static_cast<int>(field - names.begin()));
  std::vector<double> x, y, value;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double px = nodes.position[0][i], py = nodes.position[1][i];
    if (px < kFootingLeft - kFootingWidth || py < kCrestY - kBandRegionDepth) continue;
    x.push_back(px);
    y.push_back(py);
    value.push_back(strain[i]);
  }
  return measure_band(x, y, value, BandAngleOptions{});
}

}  // namespace

std::vector<CheckResult> validate_vpw_vertical_cut_footing(const ValidationContext& context) {
  std::vector<CaseOverride> overrides = {{"output.interval", "0"}};
  if (context.quick) overrides.push_back({"geometry.spacing", std::to_string(kQuickSpacing)});
  const CaseDescription description =
      load_bundled_case(context, "vpw-vertical-cut-footing", overrides);
  const double spacing = description.geometry.spacing;
  const int footing_nodes = static_cast<int>(std::lround(kFootingWidth / spacing)) + 1;

  std::optional<BandMeasurement> band;
  const ProbeTable probes =
      ProbeTable::read(run_for_validation(context, description, context.quick ? "quick" : "full",
                                          [&](const Simulation& simulation) {
                                            band = measure_wedge_band(simulation);
                                          }) /
                       "probes.csv");
  if (!band) throw RunError("vpw-vertical-cut-footing: the band was not measured");

  const double end = description.time.end;
  double plateau = 0.0;
  int samples = 0;
  const auto& time = probes.time();
  for (std::size_t row = 0; row < time.size(); ++row)
    if (time[row] >= 0.8 * end) {
      plateau += footing_pressure(probes, row, footing_nodes);
      ++samples;
    }
  if (samples == 0) throw RunError("vpw-vertical-cut-footing: no probe sample on the plateau");
  plateau /= samples;
  const double limit = references::footing_on_cut_limit_pressure(
      references::von_mises_plane_strain_cohesion(kYieldStress));

  // 10 % (5 % in validation.md for a converged dry run): the collapse load of a Perzyna material
  // is within 1 % of 2c at this rate, the rest covers the footing edge resolved to dx/2 on B/dx = 8
  // (quick) or 16 nodes and the undrained-limit approximation.
  return {
      check_at_most("limit_pressure_error", relative_error(plateau, limit), 0.0, 0.10, "fraction"),
      check_within("shear_band_angle", band->primary.angle_deg,
                   references::j2_plane_strain_band_angle_deg(), 5.0, "deg"),
  };
}

}  // namespace rktsph
