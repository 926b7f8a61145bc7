// The critical stability number of a vertical cut by bisection over runs (docs/theory.md §8.6),
// shared by slope-viscoplastic (thesis §4.5.2) and ld-slope-cohesive (thesis 5.3.5): each run sets
// the yield stress from N = gamma H sqrt(3) / Y, ramps gravity in as its case does and is
// classified stable or failing from the crest's motion over its last two seconds.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/validation/validation_case.hpp"

namespace rktsph {

/// The cut of a slope case, read from its file: the block is the first shape (a rectangle whose
/// right side is the cut face), of the material "soil", under gravity ramped in linearly.
struct SlopeCut {
  double height = 0.0, length = 0.0;  // H and the block's length [m]
  double unit_weight = 0.0;           // gamma = rho g [N/m^3]
  double ramp_end = 0.0;              // end of the gravity ramp [s]
  /// Y at the stability number N = gamma H sqrt(3) / Y.
  double yield_stress(double stability_number) const;
};

/// RunError if the case does not have that shape.
SlopeCut read_slope_cut(const CaseDescription& description);

struct SlopeRun {
  double early_rate = 0.0;  // crest horizontal displacement over [end - 2, end - 1] s [m/s]
  double late_rate = 0.0;   // ... over [end - 1, end] s
  bool stable = false;
  // For the report.
  double stability_number = 0.0;
  std::filesystem::path directory;
  std::vector<double> time, crest;  // crest horizontal displacement history [m]
};

/// One run of the case in `folder` (whose cut is `cut`) at stability number N, to `end_time`.
SlopeRun run_slope(const ValidationContext& context, const std::string& folder, const SlopeCut& cut,
                   const std::vector<CaseOverride>& base, double stability_number, double end_time);

struct SlopeBisection {
  double critical = 0.0;  ///< NaN when the bracket does not hold
  std::vector<SlopeRun> runs;
};

/// Checks that `stable` is stable and `failing` fails, then halves the bracket `steps` times.
SlopeBisection bisect_stability_number(const ValidationContext& context, const std::string& folder,
                                       const SlopeCut& cut, const std::vector<CaseOverride>& base,
                                       double stable, double failing, int steps, double end_time);

/// The outcome of every run of the bisection against Taylor's number, the crest histories, and
/// the eps_vp field of the least unstable run; `thesis_case` opens the description.
void report_bisection(ValidationReport& report, const std::string& thesis_case, const SlopeCut& cut,
                      std::vector<SlopeRun> runs, double critical, double reference,
                      double end_time);

}  // namespace rktsph
