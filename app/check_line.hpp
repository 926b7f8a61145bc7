// The line `rktsph validate` prints for one check of a case (the JSON line is a separate contract).
#pragma once

#include <fmt/format.h>

#include <string>

#include "rktsph/validation/validation_case.hpp"

namespace rktsph {

/// "0.02 fraction", "3 deg"; a pure number (unit "1" or none) is written alone, so that a bound
/// reads "at least 1" rather than "at least 1 1".
inline std::string quantity_text(double value, const std::string& unit) {
  if (unit.empty() || unit == "1") return fmt::format("{:.3g}", value);
  return fmt::format("{:.3g} {}", value, unit);
}

/// "    name     value (reference r, at least b)  ok".
inline std::string check_line(const CheckResult& check) {
  const char* bound = check.comparison == "at_least"  ? "at least"
                      : check.comparison == "at_most" ? "at most"
                                                      : "tolerance";
  return fmt::format("    {:<32} {:>12.5g} (reference {:.5g}, {} {})  {}\n", check.name,
                     check.value, check.reference, bound,
                     quantity_text(check.tolerance, check.unit), check.passed ? "ok" : "FAIL");
}

}  // namespace rktsph
