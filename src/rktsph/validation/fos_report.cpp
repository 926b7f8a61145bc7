// Helpers of the strength-reduction validation cases (fos_report.hpp).
#include "rktsph/validation/fos_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

namespace rktsph {

StrengthReductionResult run_strength_reduction(const ValidationContext& context,
                                               const CaseDescription& description,
                                               StrengthReductionOptions options,
                                               const std::string& label) {
  options.existing_results = ExistingResults::Overwrite;  // the validation owns its folders
  return find_factor_of_safety(description, options,
                               context.output_directory / description.name / label);
}

double factor_or_nan(const StrengthReductionResult& result) {
  return result.bracket_holds ? result.factor : std::numeric_limits<double>::quiet_NaN();
}

void add_bisection_figure(ValidationReport& report, const std::string& name,
                          const std::string& title, const StrengthReductionResult& result,
                          const std::vector<std::pair<std::string, double>>& references) {
  Series stable{"stable runs", {}, {}, "points"}, failing{"failing runs", {}, {}, "points"};
  double low = 1.0, high = 1.0;
  for (const ReductionRun& run : result.runs) {
    const double ratio = run.largest_displacement / result.elastic.largest_displacement;
    Series& series = run.failing ? failing : stable;
    series.x.push_back(run.factor);
    series.y.push_back(ratio);
    low = std::min(low, ratio);
    high = std::max(high, ratio);
  }
  Figure figure{name,
                title,
                "strength factor F (c' / F, tan phi' / F) [-]",
                "largest displacement at the end / elastic one [-]",
                {std::move(stable), std::move(failing)}};
  figure.y_scale = "log";
  low *= 0.5;
  high *= 2.0;
  for (const auto& [label, value] : references)
    figure.series.push_back({label, {value, value}, {low, high}, "dashed"});
  if (result.bracket_holds)
    figure.series.push_back({fmt::format("bisected F = {:.3f}", result.factor),
                             {result.factor, result.factor},
                             {low, high},
                             "line"});
  report.add_figure(std::move(figure));
}

void add_strength_reduction_speed_figure(ValidationReport& report, const std::string& name,
                                         const StrengthReductionResult& result) {
  Figure figure{name,
                "Largest speed over the nodes, one curve per run (at rest: 1e-3 of the peak)",
                "time [s]",
                "largest speed [m/s]",
                {}};
  figure.y_scale = "log";
  for (const ReductionRun& run : result.runs)
    figure.series.push_back(
        {fmt::format("F = {:.3f} ({})", run.factor, run.failing ? "failing" : "stable"), run.time,
         run.speed, "line"});
  report.add_figure(std::move(figure));
}

void add_mechanism_picture(ValidationReport& report, const std::string& name,
                           const StrengthReductionResult& result) {
  if (const ReductionRun* failing = result.first_failing())
    report.add_picture(
        {name, failing->directory.string(), "eps_vp", -1, -1.0, 1.0,
         fmt::format("Equivalent viscoplastic strain at t = {:.3g} s of the failing run with the "
                     "smallest strength factor (F = {:.4f}), on the deformed configuration "
                     "(displacements at true scale): the failure mechanism.",
                     failing->end_time, failing->factor)});
}

std::string strength_reduction_runs_text(const StrengthReductionResult& result) {
  std::string text;
  for (const ReductionRun& run : result.runs)
    text += fmt::format("{}F = {:.4f} {}", text.empty() ? "" : "; ", run.factor,
                        run.failing ? "failing" : "stable");
  return text;
}

}  // namespace rktsph
