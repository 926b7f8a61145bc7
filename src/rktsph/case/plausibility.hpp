// Plausibility of a case: values a case file may hold but that no real soil or rock has (a
// modulus of 10 Pa, a density of 2 kg/m^3, an angle of 0.44 degrees), values in the wrong unit
// (MPa for Pa, kPa for Pa, radians for degrees, t/m^3 for kg/m^3) and a run that cannot reach
// what it asks for (a load ramp longer than the run, field output more often than the time step).
// These are warnings, never errors: an unusual material is the user's call (the ranges and their
// sources are in docs/input-reference.md, "Plausibility warnings").
#pragma once

#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"

namespace rktsph {

struct CaseWarning {
  SourceLocation where;
  std::string key;    ///< dotted path, e.g. "materials.soil.young_modulus"
  std::string value;  ///< as found
  std::string text;   ///< what looks wrong and what was probably meant

  /// "case.yaml:9:5: warning: key 'materials.soil.young_modulus' = 10: text"
  std::string to_string() const;
};

/// The warnings for `description`, in file order; `time_step` is the run's dt [s] (the Courant
/// step, or the case's numerics.time_step).
std::vector<CaseWarning> plausibility_warnings(const CaseDescription& description,
                                               double time_step);

/// Plain-text lines of `warnings`, for run.log and summary.json.
std::vector<std::string> warning_lines(const std::vector<CaseWarning>& warnings);

}  // namespace rktsph
