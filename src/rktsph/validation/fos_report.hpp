// Helpers of the validation cases that find a factor of safety by strength reduction
// (docs/theory.md §10): run `rktsph fos`'s bisection into the validation's output folder, and draw
// its runs (outcome against F, speed histories, the mechanism) in the report.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "rktsph/strength_reduction/strength_reduction.hpp"
#include "rktsph/validation/validation_case.hpp"

namespace rktsph {

/// The bisection on `description` with `options`, into <output>/<case name>/<label> (replacing a
/// previous validation's runs).
StrengthReductionResult run_strength_reduction(const ValidationContext& context,
                                               const CaseDescription& description,
                                               StrengthReductionOptions options,
                                               const std::string& label);

/// F when the bracket held, NaN otherwise (a check then fails).
double factor_or_nan(const StrengthReductionResult& result);

/// "F = 1.4200 stable; F = 1.6600 failing; ..." in the order run.
std::string strength_reduction_runs_text(const StrengthReductionResult& result);

/// The runs of one strength reduction: u_max / u_el against F, stable and failing, with vertical
/// lines at the reference factors.
void add_bisection_figure(ValidationReport& report, const std::string& name,
                          const std::string& title, const StrengthReductionResult& result,
                          const std::vector<std::pair<std::string, double>>& references);

/// The largest speed against time, one curve per run.
void add_strength_reduction_speed_figure(ValidationReport& report, const std::string& name,
                                         const StrengthReductionResult& result);

/// The equivalent viscoplastic strain of the failing run with the smallest F, if there is one.
void add_mechanism_picture(ValidationReport& report, const std::string& name,
                           const StrengthReductionResult& result);

}  // namespace rktsph
