// The machinery of `rktsph validate`: each bundled case runs (one or several simulations) and
// compares what it measured with an analytical or independent reference.
//
// Output contract (other tools read it): with --json, one line per case
//   {"case": NAME, "passed": bool, "wall_seconds": x,
//    "checks": [{"name", "value", "reference", "tolerance", "unit", "passed"}]}
// Relative errors and ratios are plain fractions, angles in degrees, times in seconds.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace rktsph {

struct CheckResult {
  std::string name;
  double value = 0.0;      ///< what was measured
  double reference = 0.0;  ///< the analytical / reference value, where there is one
  double tolerance = 0.0;
  std::string unit;  ///< "fraction", "deg", "s", "1", ...
  bool passed = false;
};

struct ValidationResult {
  std::string case_name;
  bool passed = false;
  double wall_seconds = 0.0;
  std::vector<CheckResult> checks;
  std::string error;  ///< why the case could not run, if it could not
};

struct ValidationContext {
  std::filesystem::path cases_directory;   ///< where cases/<name>/case.yaml live
  std::filesystem::path output_directory;  ///< runs go to <output>/<case>/<run>
  bool quick = false;
  bool quiet = true;
};

struct ValidationCase {
  std::string name;
  std::string summary;
  /// Runs the case and fills in the checks (not `passed`/`wall_seconds`: the runner does).
  std::function<std::vector<CheckResult>(const ValidationContext&)> run;
};

/// Every bundled validation case, in a fixed order.
const std::vector<ValidationCase>& validation_cases();

/// Runs one case, catching errors into `error` (a case that cannot run fails).
ValidationResult run_validation(const ValidationCase& validation, const ValidationContext& context);

/// A check passes when |value - reference| <= tolerance (absolute) ...
CheckResult check_within(std::string name, double value, double reference, double tolerance,
                         std::string unit);
/// ... or when value <= tolerance (errors and ratios measured against a reference).
CheckResult check_at_most(std::string name, double value, double reference, double tolerance,
                          std::string unit);

/// The JSON line of the output contract.
std::string validation_json_line(const ValidationResult& result);

}  // namespace rktsph
