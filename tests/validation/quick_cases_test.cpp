// Every bundled validation case in its quick variant (coarser, shorter), as `make test` runs
// them; `rktsph validate --all` runs the full ones. Named *Slow* so that the sanitizer pass of CI
// leaves them to the Release pass.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "rktsph/validation/validation_case.hpp"

namespace rktsph {
namespace {

class QuickValidationSlow : public testing::TestWithParam<std::string> {};

// Cases with an open, documented problem: skipped here (reported as skipped, never as passed)
// while `rktsph validate` keeps reporting them as failed. Each entry names the problem.
const std::map<std::string, std::string>& known_open_problems() {
  // None at present: slope-elastic, the last one, came to rest once the boundary momentum
  // closure became the adjoint of the strain rate (docs/theory.md §5.3).
  static const std::map<std::string, std::string> problems = {};
  return problems;
}

TEST_P(QuickValidationSlow, PassesItsChecks) {
  if (const auto problem = known_open_problems().find(GetParam());
      problem != known_open_problems().end())
    GTEST_SKIP() << GetParam() << ": " << problem->second;
  const auto& cases = validation_cases();
  const auto it = std::find_if(cases.begin(), cases.end(),
                               [&](const ValidationCase& c) { return c.name == GetParam(); });
  ASSERT_NE(it, cases.end());
  ValidationContext context;
  context.cases_directory = std::filesystem::path(RKTSPH_SOURCE_DIR) / "cases";
  context.output_directory =
      std::filesystem::temp_directory_path() / ("rktsph_quick_" + std::to_string(getpid()));
  context.quick = true;
  // With the report on, as `make validate` runs them: the figures and pictures are collected too,
  // and every case must give at least one of each (issue: a plot and a picture per case).
  context.write_report = true;
  const ValidationResult result = run_validation(*it, context);
  EXPECT_TRUE(result.error.empty()) << result.error;
  EXPECT_FALSE(result.figures.empty()) << GetParam() << " describes no figure for the report";
  EXPECT_FALSE(result.pictures.empty()) << GetParam() << " describes no field picture";
  for (const CheckResult& check : result.checks)
    EXPECT_TRUE(check.passed) << check.name << " = " << check.value << " (reference "
                              << check.reference << ", tolerance " << check.tolerance << " "
                              << check.unit << ")";
  EXPECT_TRUE(result.passed);
}

std::vector<std::string> case_names() {
  std::vector<std::string> names;
  for (const ValidationCase& c : validation_cases())
    names.push_back(c.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Bundled, QuickValidationSlow, testing::ValuesIn(case_names()),
                         [](const testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace rktsph
