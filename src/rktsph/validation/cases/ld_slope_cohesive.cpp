// Thesis §5.3.5 (docs/theory.md §8.6, §9.13): the cohesive vertical cut of thesis 4.5.2 with the
// large-deformation model and a rigid rough base in contact. Checks:
//   stability_number           the critical N = gamma H sqrt(3) / Y by bisection over runs
//                              (slope_bisection.hpp: stable <-> the crest slows down over the last
//                              two seconds), against Taylor's 3.83 +- 5 %.
//   post_failure_displacement  the crest's displacement |u| at the end of a run at N = 4.5 (factor
//                              of safety 0.85, damping off after the ramp) held to the case's
//                              time.end, over H (>= 0.2: the model follows the failure into large
//                              deformation).
#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "rktsph/validation/references/limit_loads.hpp"
#include "rktsph/validation/slope_bisection.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::ld_slope_cohesive {

namespace {

constexpr char kCase[] = "ld-slope-cohesive";
constexpr double kFailingNumber = 4.5;

struct PostFailure {
  ValidationRun run;
  double end = 0.0;                        // [s], the case's time.end
  std::vector<double> time, displacement;  // crest |u| [m]
};

PostFailure run_post_failure(const ValidationContext& context, const SlopeCut& cut,
                             std::vector<CaseOverride> base) {
  const double yield_stress = cut.yield_stress(kFailingNumber);
  base.push_back({"materials.soil.yield_stress", fmt::format("{:.9g}", yield_stress)});
  base.push_back({"output.interval", "2.0"});
  // The damping brings the gravity ramp in quasi-statically; the failure after it runs undamped,
  // at the pace its overstress sets (with the damping on it creeps at a few cm/s).
  base.push_back({"loads.damping.end", fmt::format("{}", cut.ramp_end + 0.5)});
  PostFailure result;
  const CaseDescription description = load_bundled_case(context, kCase, base);
  result.end = description.time.end;
  result.run = run_allowing_failure(context, description, "post_failure");
  const ProbeTable probes = ProbeTable::read(result.run.directory / "probes.csv");
  result.time = probes.time();
  const auto& ux = probes.column("crest.displacement_x");
  const auto& uy = probes.column("crest.displacement_y");
  for (std::size_t i = 0; i < ux.size(); ++i)
    result.displacement.push_back(std::hypot(ux[i], uy[i]));
  return result;
}

}  // namespace

std::vector<CheckResult> validate_ld_slope_cohesive(const ValidationContext& context) {
  // Quick: dx = 1 m (10 cells over H), 4 bisection steps; full: dx = 0.5 m, 6 steps.
  std::vector<CaseOverride> base = {{"output.interval", "0"}};
  if (context.quick) base.push_back({"geometry.spacing", "1.0"});
  const int steps = context.quick ? 4 : 6;
  // The failing end of the bracket: on the quick lattice a cut at N = 4.6 moves 0.36 m and comes
  // to rest within the 6 s (the moving configuration restabilises a coarse cut sooner), so it
  // starts from 5.2 there.
  const double failing = context.quick ? 5.2 : 4.6;
  const SlopeCut cut = read_slope_cut(load_bundled_case(context, kCase, base));
  const double end_time = cut.ramp_end + 6.0;  // 6 s at full load after the ramp
  const SlopeBisection bisection =
      bisect_stability_number(context, kCase, cut, base, 3.0, failing, steps, end_time);
  base.erase(base.begin());  // the post-failure run writes fields for its picture
  const PostFailure failure = run_post_failure(context, cut, base);
  const double reference = references::kTaylorVerticalCutStabilityNumber;
  const double crest_ratio = failure.displacement.back() / cut.height;
  if (context.report) {
    report_bisection(*context.report, "Thesis 5.3.5 (large deformation)", cut, bisection.runs,
                     bisection.critical, reference, end_time);
    context.report->describe(
        context.report->description() +
        fmt::format(
            " A run at N = {:g} (factor of safety {:.2f}) is then followed to t = {:g} s: "
            "the crest moves {:.2f} m ({:.3f} H).{}",
            kFailingNumber, reference / kFailingNumber, failure.end, failure.displacement.back(),
            crest_ratio,
            failure.run.completed ? "" : " That run stopped early: " + failure.run.message));
    Series crest{"SPH, large deformation", failure.time, {}, "line"};
    for (double u : failure.displacement)
      crest.y.push_back(u / cut.height);
    context.report->add_figure(
        {"post_failure_crest",
         fmt::format("Crest displacement of the run at N = {:g}", kFailingNumber),
         "time [s]",
         "crest displacement |u| / H [-]",
         {std::move(crest),
          sample_curve("0.2 H", 0.0, failure.end, 2, [](double) { return 0.2; })}});
    context.report->add_picture({"eps_vp_post_failure", failure.run.directory.string(), "eps_vp",
                                 -1, -1.0, 1.0,
                                 fmt::format("Equivalent viscoplastic strain at the end of the "
                                             "run at N = {:g}, on the deformed configuration "
                                             "(true scale).",
                                             kFailingNumber)});
  }
  // stability_number: docs/theory.md §8.6, within 5 % of 3.83 as slope-viscoplastic.
  // post_failure_displacement 0.2: the floor.
  return {check_within("stability_number", bisection.critical, reference, 0.05 * reference, "1"),
          check_at_least("post_failure_displacement", crest_ratio, 0.2, 0.2, "fraction")};
}

}  // namespace rktsph::case_checks::ld_slope_cohesive
