// The line `rktsph validate` prints for a check reads as a sentence: a bound on a pure number
// carries no unit "1" ("at least 1 1" read as a typo).
#include <gtest/gtest.h>

#include "../../app/check_line.hpp"

namespace rktsph::check_line_test {
namespace {

CheckResult check(const std::string& comparison, double bound, const std::string& unit) {
  CheckResult result;
  result.name = "runout_ratio";
  result.value = 1.4;
  result.reference = 1.0;
  result.tolerance = bound;
  result.unit = unit;
  result.passed = true;
  result.comparison = comparison;
  return result;
}

TEST(CheckLine, APureNumberHasNoUnitOne) {
  const std::string line = check_line(check("at_least", 1.0, "1"));
  EXPECT_NE(line.find("(reference 1, at least 1)"), std::string::npos) << line;
  EXPECT_EQ(line.find("at least 1 1"), std::string::npos) << line;
}

TEST(CheckLine, AQuantityKeepsItsUnit) {
  EXPECT_NE(check_line(check("within", 0.05, "fraction")).find("tolerance 0.05 fraction)"),
            std::string::npos);
  EXPECT_NE(check_line(check("at_most", 3.0, "deg")).find("at most 3 deg)"), std::string::npos);
}

}  // namespace
}  // namespace rktsph::check_line_test
