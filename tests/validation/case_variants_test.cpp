// The validation cases read their physics and geometry from the case they run: a variant of a
// bundled case (ValidationContext::overrides, `rktsph validate --set`) is checked against its own
// references, and a case of another shape than its references need is refused with a clear error.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "rktsph/core/error.hpp"
#include "rktsph/validation/slope_bisection.hpp"
#include "rktsph/validation/validation_case.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_variants_test {
namespace {

ValidationContext quick_context(std::vector<CaseOverride> overrides = {}) {
  ValidationContext context;
  context.cases_directory = std::filesystem::path(RKTSPH_SOURCE_DIR) / "cases";
  context.output_directory =
      std::filesystem::temp_directory_path() / ("rktsph_variants_" + std::to_string(getpid()));
  context.quick = true;
  context.overrides = std::move(overrides);
  return context;
}

const CheckResult& check_named(const ValidationResult& result, const std::string& name) {
  const auto it = std::find_if(result.checks.begin(), result.checks.end(),
                               [&](const CheckResult& check) { return check.name == name; });
  if (it == result.checks.end()) throw RunError(result.case_name + " reports no " + name);
  return *it;
}

ValidationResult run_named(const std::string& name, const ValidationContext& context) {
  const auto& cases = validation_cases();
  const auto it = std::find_if(cases.begin(), cases.end(),
                               [&](const ValidationCase& c) { return c.name == name; });
  if (it == cases.end()) throw RunError("no validation case " + name);
  return run_validation(*it, context);
}

// ---------------------------------------------------------------------------------------------
// What the cases read

TEST(CaseShape, OverridesOfTheContextComeBeforeTheCasesOwn) {
  const ValidationContext context =
      quick_context({{"materials.soil.poisson_ratio", "0.45"}, {"geometry.spacing", "2.0"}});
  const CaseDescription description =
      load_bundled_case(context, "slope-elastic", {{"geometry.spacing", "1.0"}});
  EXPECT_EQ(material_parameter(description, "soil", "poisson_ratio"), 0.45);
  EXPECT_EQ(description.geometry.spacing, 1.0);
}

TEST(CaseShape, StripLoadOfTheBundledCaseAndOfAVariant) {
  CaseDescription description = load_bundled_case(quick_context(), "strip-footing-elastic");
  const StripLoad bundled = read_strip_load(description);
  EXPECT_EQ(bundled.pressure, 5.0e4);
  EXPECT_EQ(bundled.half_width, 2.0);
  EXPECT_EQ(bundled.row.surface, 24.0);
  EXPECT_EQ(bundled.row.body.width(), 24.0);
  ASSERT_NE(bundled.history, nullptr);
  EXPECT_EQ((*bundled.history)(10.0), -5.0e4);
  // Twice the load, on a wider strip.
  for (BoundaryConditionSpec& condition : description.boundary_conditions)
    if (condition.traction[1]) condition.traction[1]->value *= 2.0;
  for (GroupSpec& group : description.groups)
    if (group.name == "footing") group.max[0] = 3.0;
  const StripLoad variant = read_strip_load(description);
  EXPECT_EQ(variant.pressure, 1.0e5);
  EXPECT_EQ(variant.half_width, 3.0);
}

TEST(CaseShape, StripLoadInTensionIsRefused) {
  CaseDescription description = load_bundled_case(quick_context(), "vpw-strip-footing-elastic");
  for (BoundaryConditionSpec& condition : description.boundary_conditions)
    if (condition.group == "footing") condition.traction[1]->value *= -1.0;
  EXPECT_THROW(read_strip_load(description), RunError);
}

TEST(CaseShape, FootingAtTheCrestOfACut) {
  const CaseDescription description = load_bundled_case(quick_context(), "ld-vertical-cut-footing");
  const FootingRow footing = footing_row(description, FootingPlace::Crest);
  EXPECT_EQ(footing.left, 6.0);
  EXPECT_EQ(footing.right, 8.0);
  EXPECT_EQ(footing.length(), 2.0);
  EXPECT_EQ(footing.surface, 6.0);
  // Not on the symmetry plane, and no longer at the crest once the body is wider.
  EXPECT_THROW(footing_row(description, FootingPlace::SymmetryPlane), RunError);
  CaseDescription wider = description;
  wider.geometry.shapes.at(0).vertices.at(1)[0] = 9.0;
  EXPECT_THROW(footing_row(wider, FootingPlace::Crest), RunError);
}

TEST(CaseShape, FootingFromTheSymmetryPlane) {
  CaseDescription description = load_bundled_case(quick_context(), "ld-strip-footing-bearing");
  const FootingRow footing = footing_row(description, FootingPlace::SymmetryPlane);
  EXPECT_EQ(footing.left, 0.0);
  EXPECT_EQ(footing.right, 2.0);
  // A footing box that is not one row on the top of the body.
  for (GroupSpec& group : description.groups)
    if (group.name == "footing") group.min[1] = 5.0;
  EXPECT_THROW(footing_row(description, FootingPlace::SymmetryPlane), RunError);
}

TEST(CaseShape, WeakZoneOfTheLocalisationCases) {
  for (const char* folder : {"sample2d-localization", "vpw-localization"}) {
    CaseDescription description = load_bundled_case(quick_context(), folder);
    const WeakZone weak = read_weak_zone(description);
    EXPECT_EQ(weak.centre_x(), 0.05) << folder;
    EXPECT_EQ(weak.centre_y(), 0.05) << folder;
    EXPECT_DOUBLE_EQ(weak.half_diagonal(), 0.05 * std::sqrt(2.0)) << folder;
    description.geometry.shapes.pop_back();
    EXPECT_THROW(read_weak_zone(description), RunError) << folder;
  }
}

TEST(CaseShape, SlopeCutFollowsTheCase) {
  const SlopeCut bundled = read_slope_cut(load_bundled_case(quick_context(), "slope-viscoplastic"));
  EXPECT_EQ(bundled.height, 10.0);
  EXPECT_EQ(bundled.length, 20.0);
  EXPECT_EQ(bundled.unit_weight, 2000.0 * 9.81);
  EXPECT_EQ(bundled.ramp_end, 2.0);
  const SlopeCut variant = read_slope_cut(load_bundled_case(
      quick_context({{"materials.soil.density", "1800"}, {"loads.gravity.factor.duration", "3"}}),
      "ld-slope-cohesive"));
  EXPECT_EQ(variant.unit_weight, 1800.0 * 9.81);
  EXPECT_EQ(variant.ramp_end, 3.0);
  // N = gamma H sqrt(3) / Y
  EXPECT_DOUBLE_EQ(variant.yield_stress(4.0), 1800.0 * 9.81 * 10.0 * std::sqrt(3.0) / 4.0);
}

TEST(CaseShape, GravityMustPointDown) {
  CaseDescription description = load_bundled_case(quick_context(), "slope-elastic");
  EXPECT_EQ(downward_gravity(description), 9.81);
  description.gravity->acceleration = {1.0, -9.81, 0.0};
  EXPECT_THROW(downward_gravity(description), RunError);
  description.gravity.reset();
  EXPECT_THROW(downward_gravity(description), RunError);
}

// ---------------------------------------------------------------------------------------------
// Variants checked against their own references

struct OneThread {
  int saved = omp_get_max_threads();
  OneThread() { omp_set_num_threads(1); }
  ~OneThread() { omp_set_num_threads(saved); }
};

// nu = 0.2 and rho = 2500 kg/m3: K0 = 0.25 and a 25 % heavier overburden. Against the bundled
// case's references the checks measured 0.43 (k0_error) and 0.25 (vertical_stress_error).
TEST(CaseVariant, SlopeElasticAtAnotherPoissonRatioAndDensity) {
  const OneThread one_thread;
  const ValidationResult result = run_named(
      "slope-elastic",
      quick_context({{"materials.soil.poisson_ratio", "0.2"}, {"materials.soil.density", "2500"}}));
  ASSERT_TRUE(result.error.empty()) << result.error;
  for (const CheckResult& check : result.checks)
    EXPECT_TRUE(check.passed) << check.name << " " << check.value;
}

// The water table higher, a given density above it, alpha < 1 and another nu: the closed form
// follows the case (docs/theory.md eq. 8.8), and the run is lengthened to drain the deeper layer.
// The slope's strength reductions follow the density, alpha and nu too, with Bishop's factor
// (its table stays its own). Slow: the two strength reductions of the slope.
TEST(CaseVariantSlow, WaterTableAtAnotherLevelDensityAndBiotCoefficient) {
  const OneThread one_thread;
  const ValidationResult result =
      run_named("vpw-water-table", quick_context({{"pore_fluid.water_table.level", "7.5"},
                                                  {"pore_fluid.water_table.density_above", "1800"},
                                                  {"pore_fluid.biot_coefficient", "0.9"},
                                                  {"materials.soil.poisson_ratio", "0.25"}}));
  ASSERT_TRUE(result.error.empty()) << result.error;
  for (const CheckResult& check : result.checks)
    EXPECT_TRUE(check.passed) << check.name << " " << check.value;
}

TEST(CaseShape, WaterTableCaseNeedsALevelInsideTheLayer) {
  const ValidationResult result =
      run_named("vpw-water-table", quick_context({{"pore_fluid.water_table.level", "-1"}}));
  EXPECT_NE(result.error.find("not above the base"), std::string::npos) << result.error;
}

// nu = 0.45: K0 = 0.818 against the bundled 0.429, where k0_error measured 0.90. The full lattice
// (10 cells over H in the quick variant give 0.033). vertical_stress_error is left out: it is the
// face's relief of the overburden 2H behind it, which grows with K0 (0.027 at nu = 0.45 on both
// lattices, 0.015 at 0.3), not a lattice error.
TEST(CaseVariantSlow, SlopeElasticAtPoissonRatio045MeetsItsOwnK0) {
  const OneThread one_thread;
  ValidationContext context = quick_context({{"materials.soil.poisson_ratio", "0.45"}});
  context.quick = false;
  const ValidationResult result = run_named("slope-elastic", context);
  ASSERT_TRUE(result.error.empty()) << result.error;
  const CheckResult& k0 = check_named(result, "k0_error");
  EXPECT_TRUE(k0.passed) << "k0_error " << k0.value;
}

// A strip 1.5 times as wide under twice the load: b = 3 m, q = 100 kPa (drawn over 0 <= x <= b).
// Against the bundled strip the centre-line check measured 1.03 q.
TEST(CaseVariantSlow, StripFootingElasticWiderStripUnderTwiceTheLoad) {
  const OneThread one_thread;
  const ValidationResult result = run_named(
      "strip-footing-elastic", quick_context({{"boundary_conditions.3.traction.y.value", "-100000"},
                                              {"groups.footing.box.max", "[3, 24]"}}));
  ASSERT_TRUE(result.error.empty()) << result.error;
  const CheckResult& stress = check_named(result, "centreline_stress_error");
  EXPECT_TRUE(stress.passed) << "centreline_stress_error " << stress.value;
}

}  // namespace
}  // namespace rktsph::case_variants_test
