// The critical stability number of the 10 m vertical cut in a Perzyna Von Mises soil without
// hardening (docs/theory.md §8.6), found by bisection over runs: slope-viscoplastic (thesis §4.5.2)
// and ld-slope-cohesive (thesis 5.3.5) run it on their own case folders.
#include "rktsph/validation/slope_bisection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include "rktsph/validation/validation_support.hpp"

namespace rktsph {

namespace {

double displacement_at(const ProbeTable& probes, const std::string& column, double time) {
  const auto& t = probes.time();
  const auto& u = probes.column(column);
  for (std::size_t i = 1; i < t.size(); ++i)
    if (t[i] >= time) return u[i - 1] + (u[i] - u[i - 1]) * (time - t[i - 1]) / (t[i] - t[i - 1]);
  return u.back();
}

}  // namespace

double SlopeCut::yield_stress(double stability_number) const {
  return unit_weight * height * std::sqrt(3.0) / stability_number;
}

SlopeCut read_slope_cut(const CaseDescription& description) {
  SlopeCut cut;
  const Rectangle block = rectangle_shape(description, 0);
  cut.height = block.height();
  cut.length = block.width();
  cut.unit_weight =
      material_parameter(description, "soil", "density") * downward_gravity(description);
  const TimeFunction& ramp = description.gravity->factor;
  if (ramp.kind != TimeFunction::Kind::LinearRamp)
    throw RunError("case " + description.name + ": the gravity must be ramped in linearly");
  cut.ramp_end = ramp.start + ramp.duration;
  return cut;
}

// Stable <-> the slope is coming to rest: with the load constant after the ramp, the crest's
// horizontal speed over the last second is below 0.9 of the second before (an e-folding time
// under about 10 s), or below 1e-5 H per second (at rest to within the run's rounding). Speeds,
// not signed rates: a cut that comes to rest may recover part of its bulge elastically, and its
// crest then moves back, slower and slower. A failing cut flows at a steady rate set by the
// overstress and the fluidity (ratio 1), or accelerates. Near N_c the viscoplastic relaxation slows
// down, so a finite run classifies marginally stable cuts as failing: the bisection errs on the low
// side.

SlopeRun run_slope(const ValidationContext& context, const std::string& folder, const SlopeCut& cut,
                   const std::vector<CaseOverride>& base, double stability_number,
                   double end_time) {
  const double yield_stress = cut.yield_stress(stability_number);
  std::vector<CaseOverride> overrides = base;
  overrides.push_back({"materials.soil.yield_stress", fmt::format("{:.9g}", yield_stress)});
  overrides.push_back({"time.end", fmt::format("{}", end_time)});
  const CaseDescription description = load_bundled_case(context, folder, overrides);
  const std::filesystem::path directory =
      run_for_validation(context, description, fmt::format("N{:.4f}", stability_number));
  const ProbeTable probes = ProbeTable::read(directory / "probes.csv");
  const std::string column = "crest.displacement_x";
  SlopeRun run;
  run.stability_number = stability_number;
  run.directory = directory;
  run.time = probes.time();
  run.crest = probes.column(column);
  run.early_rate = displacement_at(probes, column, end_time - 1.0) -
                   displacement_at(probes, column, end_time - 2.0);
  run.late_rate =
      displacement_at(probes, column, end_time) - displacement_at(probes, column, end_time - 1.0);
  run.stable = std::abs(run.late_rate) < 0.9 * std::abs(run.early_rate) ||
               std::abs(run.late_rate) < 1e-5 * cut.height;
  return run;
}

void report_bisection(ValidationReport& report, const std::string& thesis_case, const SlopeCut& cut,
                      std::vector<SlopeRun> runs, double critical, double reference,
                      double end_time) {
  report.describe(fmt::format(
      "{}: a {:g} m vertical cut ({:g} m x {:g} m block, rigid rough base, roller on its left "
      "side) in a Perzyna Von Mises soil without hardening (gamma = 1/s, N = 1), gravity ramped "
      "over {:g} s and held to {:g} s. Each run sets the yield stress from a stability number "
      "N = rho g H sqrt(3) / Y; a run is stable when the crest's horizontal velocity over the "
      "last second is below 0.9 of that over the second before (the cut comes to rest), "
      "unstable otherwise (steady or accelerating flow). The critical N is bisected between a "
      "stable and an unstable bracket and compared with Taylor's toe circle, N = {:.2f} "
      "(+-5 %).",
      thesis_case, cut.height, cut.length, cut.height, cut.ramp_end, end_time, reference));
  std::sort(runs.begin(), runs.end(), [](const SlopeRun& a, const SlopeRun& b) {
    return a.stability_number < b.stability_number;
  });
  // The crest velocity over the last second (displacement per second, in mm/s), which the
  // classification compares with the second before.
  Series stable{"stable runs", {}, {}, "points"}, unstable{"unstable runs", {}, {}, "points"};
  double low = 0.0, high = 0.0;
  for (const SlopeRun& run : runs) {
    const double rate = 1e3 * run.late_rate;
    low = std::min(low, rate);
    high = std::max(high, rate);
    Series& outcome = run.stable ? stable : unstable;
    outcome.x.push_back(run.stability_number);
    outcome.y.push_back(rate);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double margin = 0.05 * (high - low);
  low -= margin;
  high += margin;
  Figure bisection{
      "bisection",
      "Outcome of each run of the bisection",
      "stability number N = rho g H sqrt(3) / Y [-]",
      "crest velocity towards the cut over the last second [mm/s]",
      {std::move(stable),
       std::move(unstable),
       {fmt::format("Taylor N = {:.2f}", reference), {reference, reference}, {low, high}, "dashed"},
       {"Taylor +-5 %",
        {0.95 * reference, 0.95 * reference, nan, 1.05 * reference, 1.05 * reference},
        {low, high, nan, low, high},
        "dashed"}}};
  if (std::isfinite(critical))
    bisection.series.push_back(
        {fmt::format("bisected N = {:.3f}", critical), {critical, critical}, {low, high}, "line"});
  report.add_figure(std::move(bisection));
  Figure crest{"crest_displacement",
               "Horizontal displacement of the crest, one curve per run",
               "time [s]",
               "crest displacement u_x towards the cut [m]",
               {}};
  for (const SlopeRun& run : runs)
    crest.series.push_back(
        {fmt::format("N = {:.4g} ({})", run.stability_number, run.stable ? "stable" : "unstable"),
         run.time, run.crest, "line"});
  report.add_figure(std::move(crest));
  const auto failing =
      std::find_if(runs.begin(), runs.end(), [](const SlopeRun& run) { return !run.stable; });
  if (failing != runs.end())
    report.add_picture(
        {"eps_vp_first_unstable", failing->directory.string(), "eps_vp", -1, -1.0, 1.0,
         fmt::format("Equivalent viscoplastic strain at t = {:g} s in the unstable run with the "
                     "smallest stability number (N = {:.4g}), on the deformed configuration "
                     "(displacements drawn at true scale): the failure mechanism of the cut.",
                     end_time, failing->stability_number)});
}

SlopeBisection bisect_stability_number(const ValidationContext& context, const std::string& folder,
                                       const SlopeCut& cut, const std::vector<CaseOverride>& base,
                                       double stable, double failing, int steps, double end_time) {
  SlopeBisection bisection;
  const auto run_and_keep = [&](double stability_number) {
    bisection.runs.push_back(run_slope(context, folder, cut, base, stability_number, end_time));
    return bisection.runs.back().stable;
  };
  // The bracket is checked before bisecting.
  const bool bracket_holds = run_and_keep(stable) && !run_and_keep(failing);
  for (int k = 0; k < steps && bracket_holds; ++k) {
    const double middle = 0.5 * (stable + failing);
    (run_and_keep(middle) ? stable : failing) = middle;
  }
  bisection.critical =
      bracket_holds ? 0.5 * (stable + failing) : std::numeric_limits<double>::quiet_NaN();
  return bisection;
}

}  // namespace rktsph
