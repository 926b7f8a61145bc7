// Every bundled validation case in its quick variant (coarser, shorter), as `make test` runs
// them; `rktsph validate --all` runs the full ones. Named *Slow* so that the sanitizer pass of CI
// leaves them to the Release pass.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <map>

#include "../support/validation_runs.hpp"
#include "rktsph/validation/validation_case.hpp"

namespace rktsph::quick_cases_test {
namespace {

class QuickValidationSlow : public testing::TestWithParam<std::string> {};

// Cases with an open, documented problem: skipped here (reported as skipped, never as passed)
// while `rktsph validate` keeps reporting them as failed. Each entry names the problem.
const std::map<std::string, std::string>& known_open_problems() {
  static const std::map<std::string, std::string> problems = {};
  return problems;
}

// Checks that miss their tolerance on the quick variant for a documented open problem, while
// every other check of the case is still held. Each is held to still fail, so that the entry goes
// once the problem is solved; `rktsph validate` reports them as failed. The footing driven into a
// plastic, saturated cut: under the undrained plastic flow at its edge the contact pressure keeps
// an odd-even pattern (the hourglass stiffness is kept low in viscoplastic cells so as not to
// resist shear bands; docs/theory.md §3.4, "Still open").
const std::map<std::string, std::map<std::string, std::string>>& known_open_checks() {
  static const std::string plastic_edge =
      "an odd-even contact pressure under the undrained plastic flow at the footing's edge "
      "(docs/theory.md §3.4, still open)";
  static const std::string dry_plastic_edge =
      "an odd-even contact pressure under the plastic flow at a rigid footing's edge, dry and on "
      "the moving configuration, with the edge's neighbour at about twice the limit pressure "
      "(docs/theory.md §9.12, §3.4 still open)";
  static const std::string punch_edge =
      "the cell beside the strip footing's edge takes the whole velocity jump between the footing "
      "and the heave and is turned inside out at 0.17 B: a Lagrangian cell cannot follow a punch "
      "edge (docs/theory.md §9.12)";
  static const std::string no_slip_fold =
      "the collapsing block's bottom layer of cells, between the nodes held by the rough base and "
      "the flow over them, is sheared flat and folds while the front is still moving (at 1.5 s, "
      "front 19 m of the 42 m asked, quick; 1.0 s full): a Lagrangian cell cannot follow a "
      "no-slip layer into run-out (docs/theory.md §9.14)";
  static const std::map<std::string, std::map<std::string, std::string>> checks = {
      {"hanging-beam",
       {{"hourglass_velocity_ratio",
         "with 4 cells across the beam the odd-even part of v_y reaches 1.07e-3 of the smooth "
         "part (3.6e-4 with the full case's 10; docs/validation.md)"}}},
      {"ld-cantilever-plate",
       {{"period_error",
         "the quick variant's finest lattice has 4 cells across the plate: its period is 5 % "
         "above the thin-plate one (lattice error, about second order in dx; 2.0 % at the full "
         "case's 8 cells; docs/theory.md §9.11)"},
        {"period_change_finest",
         "3 and 4 cells across the plate are far from converged: their periods differ by 3 % "
         "(1.1 % between 6 and 8 cells in the full case; docs/theory.md §9.11)"}}},
      {"triangles-bar-wave-2d",
       {{"max_vy_ratio",
         "the piston's velocity step, a few cells wide, enters refinement's irregular cells just "
         "past the boundary layer (x = 1.6 dx) and kicks v_y to 0.0062 V0 (0.0102 on the full "
         "mesh; 0.019 before the layer, whose symmetric cells at the piston give none); it decays "
         "as the front spreads (3.4e-3 V0 beyond 0.05 m, 4.6e-4 V0 by mid-bar). Not a mode: it "
         "scales with the steepness of the front on irregular cells; textbook finite elements on "
         "the same meshes give 0.04-0.05 V0 (make bench-fe-triangles; docs/theory.md "
         "§8.11)"}}},
      {"vpw-vertical-cut-footing", {{"contact_pressure_oddeven_ratio", plastic_edge}}},
      {"ld-vertical-cut-footing", {{"contact_pressure_oddeven_ratio", dry_plastic_edge}}},
      {"ld-slope-cohesive",
       {{"stability_number",
         "on the 10-cell quick lattice a failing cut restabilises within the 6 s window (the "
         "moving configuration flattens it), so fast failures above N = 4.6 look stable and the "
         "bisection lands at 3.62 (the full case's 20 cells: 3.79; docs/theory.md §9.13)"},
        {"post_failure_displacement",
         "the Von Mises cut at N = 4.5 slides about 1 m and comes to rest (its geometry "
         "restabilises without softening): crest 0.11 H quick, 0.105 H full (docs/theory.md "
         "§9.13)"}}},
      {"ld-slope-low-cohesion",
       {{"deposit_bound_exceedance", no_slip_fold},
        {"runout_ratio", no_slip_fold},
        {"final_kinetic_energy_ratio", no_slip_fold},
        {"free_surface_error",
         "the detector flags interior nodes beside the crushed bottom cells (volume ratio below "
         "0.2) as surface: 1, 3 and 4 of the 40 outline nodes at 1.0, 1.3 and 1.45 s, 6 on the "
         "folded state the check sees; 3 of 80 on the full lattice (docs/theory.md §9.14)"}}},
      {"ld-footing-penetration",
       {{"settlement_reached",
         "a cell beside the footing's edge takes the velocity jump between the footing and the "
         "heave and is turned inside out at 0.61 B (quick; 0.33 B on the full case's finer "
         "lattice): a Lagrangian cell cannot follow a punch edge to 1 B (docs/theory.md §9.12, "
         "§9.16)"}}},
      {"ld-strip-footing-bearing",
       {{"contact_pressure_oddeven_ratio", dry_plastic_edge},
        {"settlement_reached", punch_edge},
        {"bearing_capacity_error",
         "the run stops at 0.17 B (punch edge), so the line is fitted over 0.10-0.17 B only, where "
         "the pressure already sags before the fold: intercept 1.054 (q/(2 + pi)c = 1.08 at "
         "0.10 B, 1.12 at 0.15 B; docs/theory.md §9.12)"}}},
  };
  return checks;
}

TEST_P(QuickValidationSlow, PassesItsChecks) {
  if (const auto problem = known_open_problems().find(GetParam());
      problem != known_open_problems().end())
    GTEST_SKIP() << GetParam() << ": " << problem->second;
  const test::OneOpenMpThread one_thread;  // tests/support/validation_runs.hpp
  const ValidationCase* validation = test::bundled_validation(GetParam());
  ASSERT_NE(validation, nullptr);
  ValidationContext context = test::quick_validation_context("rktsph_quick_");
  // With the report on, as `make validate` runs them: the figures and pictures are collected too,
  // and every case must give at least one of each (issue: a plot and a picture per case).
  context.write_report = true;
  const ValidationResult result = run_validation(*validation, context);
  EXPECT_TRUE(result.error.empty()) << result.error;
  EXPECT_FALSE(result.figures.empty()) << GetParam() << " describes no figure for the report";
  EXPECT_FALSE(result.pictures.empty()) << GetParam() << " describes no field picture";
  const auto open = known_open_checks().find(GetParam());
  bool all_others_passed = true;
  for (const CheckResult& check : result.checks) {
    const std::string measured = check.name + " = " + std::to_string(check.value) + " (tolerance " +
                                 std::to_string(check.tolerance) + ")";
    if (open != known_open_checks().end() && open->second.count(check.name)) {
      std::cout << "[ OPEN     ] " << GetParam() << ": " << measured << ": "
                << open->second.at(check.name) << "\n";
      EXPECT_FALSE(check.passed) << measured << " now passes: remove it from known_open_checks";
      continue;
    }
    EXPECT_TRUE(check.passed) << measured << " " << check.unit;
    all_others_passed = all_others_passed && check.passed;
  }
  EXPECT_TRUE(all_others_passed);
  if (open != known_open_checks().end()) {
    for (const auto& [name, reason] : open->second) {
      // An init-capture: clang 14 cannot capture a structured binding (C++20 allows it).
      EXPECT_TRUE(
          std::any_of(result.checks.begin(), result.checks.end(),
                      [&, open_name = name](const CheckResult& c) { return c.name == open_name; }))
          << "known_open_checks names " << name << ", which the case does not report";
    }
  }
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
}  // namespace rktsph::quick_cases_test
