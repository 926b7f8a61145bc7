// The machinery of `rktsph validate`: each bundled case runs (one or several simulations) and
// compares what it measured with an analytical or independent reference.
//
// Output contract (other tools read it): with --json, one line per case
//   {"case": NAME, "passed": bool, "wall_seconds": x,
//    "checks": [{"name", "value", "reference", "tolerance", "unit", "passed"}]}
// Relative errors and ratios are plain fractions, angles in degrees, times in seconds.
//
// Report (`rktsph validate --report DIR`): a case may also describe figures and field pictures
// for people to look at. The C++ side knows the physics, so it supplies the data of every curve,
// measured and analytical; tools/make_report.py only draws them. How a case adds them:
//
//   std::vector<CheckResult> validate_my_case(const ValidationContext& context) {
//     ...run, measure...
//     if (context.report) {  // null unless reporting: build no figure data otherwise
//       context.report->describe("What the case is and what it is compared with.");
//       context.report->add_figure({"mid_stress", "Stress at mid-bar", "time [s]",
//                                   "stress [Pa]",
//                                   {{"SPH", probes.time(), probes.column("mid.stress_xx"),
//                                     "line"},
//                                    sample_curve("exact", 0.0, end, 2000, exact_stress,
//                                                 "dashed")}});
//       context.report->add_picture({"final_stress", run_directory.string(), "stress", 0,
//                                    -1.0, 20.0, "sigma_xx on the deformed lattice"});
//     }
//     return checks;
//   }
//
// `run_validation` then writes <output>/<case>/report.json (the JSON-line fields plus
// "description", "figures" and "pictures"); the field pictures need the run's series.pvd, so
// the run must write field output at the time asked for.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rktsph/case/case_reader.hpp"

namespace rktsph {

struct CheckResult {
  std::string name;
  double value = 0.0;      ///< what was measured
  double reference = 0.0;  ///< the analytical / reference value, where there is one
  double tolerance = 0.0;  ///< the bound, read as `comparison` says
  std::string unit;        ///< "fraction", "deg", "s", "1", ...
  bool passed = false;
  /// How `tolerance` bounds `value`: "within" (|value - reference| <= tolerance), "at_most"
  /// (value <= tolerance) or "at_least" (value >= tolerance). Shown by the command line; not a
  /// field of the JSON line, whose fields are a contract.
  std::string comparison = "within";
};

/// One curve of a figure. x and y have the same length; NaN leaves a gap.
struct Series {
  std::string label;
  std::vector<double> x, y;
  std::string style;  ///< "line", "dashed" (references, by convention) or "points"
};

/// A 2D plot, drawn to <report>/<case>/<name>.png.
struct Figure {
  std::string name;  ///< file stem: letters, digits, '_', '-', '.'; unique within the case
  std::string title, x_label, y_label;
  std::vector<Series> series;
  /// Axis scales, "linear" or "log" (a log axis leaves out values <= 0).
  std::string x_scale = "linear", y_scale = "linear";
};

/// A picture of one output field of a run, drawn by tools/plot_field.py (as `rktsph plot`) to
/// <report>/<case>/<name>.png.
struct FieldPicture {
  std::string name;           ///< file stem, as Figure::name, unique among figures and pictures
  std::string run_directory;  ///< the run folder holding series.pvd (as run_for_validation gives)
  std::string field;          ///< a field of the field output: "stress", "velocity", ...
  int component = -1;         ///< index in the VTK tuple (stress: 0 = xx, 4 = yy, 1 = xy);
                              ///< -1: the value of a scalar, the magnitude of a vector/tensor
  double time = -1;           ///< the output nearest this time [s]; negative: the last one
  double magnification = 0;   ///< positions drawn at X + magnification * u (X reference, u
                              ///< displacement) for every model: 1 draws the current
                              ///< positions, a large-deformation run's at true scale
  std::string caption;
};

/// Where a case puts its figures, pictures and description while it runs (the sink of
/// ValidationContext::report). Throws std::invalid_argument for a malformed figure or picture
/// (bad or repeated name, unknown style or axis scale, x and y of different lengths): programming
/// errors.
class ValidationReport {
 public:
  /// A paragraph saying what the case is; replaces the registry's one-line summary.
  void describe(std::string description);
  void add_figure(Figure figure);
  void add_picture(FieldPicture picture);

  const std::string& description() const { return description_; }
  const std::vector<Figure>& figures() const { return figures_; }
  const std::vector<FieldPicture>& pictures() const { return pictures_; }

 private:
  void claim_name(const std::string& name);

  std::string description_;
  std::vector<Figure> figures_;
  std::vector<FieldPicture> pictures_;
  std::vector<std::string> names_;
};

/// A curve sampled from a function at `count` >= 2 evenly spaced x in [x0, x1]: for analytical
/// references. Steps look vertical once the spacing is small against the plot width.
Series sample_curve(std::string label, double x0, double x1, int count,
                    const std::function<double(double)>& function, std::string style = "dashed");

struct ValidationResult {
  std::string case_name;
  bool passed = false;
  double wall_seconds = 0.0;
  std::vector<CheckResult> checks;
  std::string error;  ///< why the case could not run, if it could not
  // Filled only when reporting (ValidationContext::write_report).
  std::string description;  ///< the case's own, else the registry summary
  std::vector<Figure> figures;
  std::vector<FieldPicture> pictures;
};

struct ValidationContext {
  std::filesystem::path cases_directory;   ///< where cases/<name>/case.yaml live
  std::filesystem::path output_directory;  ///< runs go to <output>/<case>/<run>
  bool quick = false;
  bool quiet = true;
  /// Applied to every case file a case loads, before the case's own settings of its runs (the
  /// quick variant's, a bisection's): a variant of the case, checked against its own references.
  std::vector<CaseOverride> overrides;
  /// Set by the caller of run_validation to have <output>/<case>/report.json written.
  bool write_report = false;
  /// Set by run_validation for the case while it runs when write_report is on; null otherwise.
  ValidationReport* report = nullptr;
};

struct ValidationCase {
  std::string name;
  std::string summary;
  /// Runs the case and fills in the checks (not `passed`/`wall_seconds`: the runner does).
  std::function<std::vector<CheckResult>(const ValidationContext&)> run;
};

/// Every bundled validation case, in a fixed order.
const std::vector<ValidationCase>& validation_cases();

/// Runs one case, catching errors into `error` (a case that cannot run fails). With
/// context.write_report, also collects the case's figures and pictures and writes
/// <output>/<case>/report.json (even when the case failed or threw); a failure to write it is
/// reported in `error` and fails the case.
ValidationResult run_validation(const ValidationCase& validation, const ValidationContext& context);

/// A check passes when |value - reference| <= tolerance (absolute) ...
CheckResult check_within(std::string name, double value, double reference, double tolerance,
                         std::string unit);
/// ... or when value <= tolerance (errors and ratios measured against a reference).
CheckResult check_at_most(std::string name, double value, double reference, double tolerance,
                          std::string unit);
/// ... or when value >= minimum (a quantity that must be reached: a settlement, a drop).
CheckResult check_at_least(std::string name, double value, double reference, double minimum,
                           std::string unit);

/// Runs `cases` with up to `jobs` of them at once, each on `threads` OpenMP threads of its own,
/// and hands each result to `done` in the order of `cases`, as soon as it and every case before
/// it have finished (`done` is called on the calling thread). The cases' runs write to separate
/// folders and share no state, so running them side by side changes no result; on a machine
/// whose cores would otherwise wait at the barriers of small runs it shortens the whole.
void run_validations(const std::vector<const ValidationCase*>& cases,
                     const ValidationContext& context, int jobs, int threads,
                     const std::function<void(const ValidationResult&)>& done);

/// The JSON line of the output contract.
std::string validation_json_line(const ValidationResult& result);

/// The content of report.json: the JSON-line fields plus "description", "figures" and
/// "pictures". Picture run directories under `report_root` are written relative to it (so that a
/// report folder can be moved); others are written absolute.
std::string validation_report_json(const ValidationResult& result,
                                   const std::filesystem::path& report_root);

}  // namespace rktsph
