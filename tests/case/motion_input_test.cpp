// The case keys of imposed and initial motion (docs/input-reference.md, "boundary_conditions" and
// "initial_conditions"): the `rotation` condition and the initial stress, angular velocity and
// bending mode: values read, bad values refused at their key, 1D refused where the key is 2D only,
// and the resolved case writing them back.
#include <gtest/gtest.h>

#include <string>

#include "../support/case_text.hpp"
#include "../support/elastic_block.hpp"
#include "rktsph/case/case_reader.hpp"

namespace rktsph::motion_input_test {
namespace {

constexpr const char* kFile = "case.yaml";

/// A free 4 m x 1 m plate; the tests append their sections.
const std::string kPlate = [] {
  test::ElasticBlock block;
  block.spacing = 0.5;
  block.shapes = test::ElasticBlock::rectangle(4.0, 1.0);
  return block.text();
}();
const std::string kBar = test::free_bar();

InputError read_error(const std::string& text) {
  try {
    read_case_text(text, kFile);
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError(SourceLocation{}, "", "", "", "");
}

void expect_error(const std::string& text, const std::string& key, const std::string& value,
                  const std::string& problem, const std::string& line_of_text) {
  const InputError error = read_error(text);
  EXPECT_EQ(error.location().file, kFile);
  EXPECT_EQ(error.location().line, test::line_of(text, line_of_text)) << error.what();
  EXPECT_EQ(error.key(), key) << error.what();
  if (!value.empty()) {
    EXPECT_EQ(error.value(), value) << error.what();
  }
  EXPECT_NE(error.problem().find(problem), std::string::npos) << error.what();
  EXPECT_FALSE(error.allowed().empty());
}

CaseDescription reread(const CaseDescription& description) {
  return read_case_text(write_case_yaml(description), "written.yaml");
}

// ---------------------------------------------------------------------------------------------
// boundary_conditions[].rotation

TEST(CaseReaderRotation, ReadsRateAndCentreAndWritesThemBack) {
  const std::string text =
      kPlate +
      "boundary_conditions:\n"
      "  - {group: xmin, rotation: {angular_velocity: -0.25, centre: [0, 0.5]}}\n";
  const CaseDescription description = read_case_text(text, kFile);
  ASSERT_EQ(description.boundary_conditions.size(), 1u);
  const BoundaryConditionSpec& condition = description.boundary_conditions[0];
  EXPECT_EQ(condition.kind, BoundaryConditionSpec::Kind::Rotation);
  EXPECT_EQ(condition.group, "xmin");
  EXPECT_EQ(condition.angular_velocity, -0.25);
  EXPECT_EQ(condition.centre, (Vec3{0.0, 0.5, 0.0}));
  const CaseDescription again = reread(description);
  ASSERT_EQ(again.boundary_conditions.size(), 1u);
  EXPECT_EQ(again.boundary_conditions[0].kind, BoundaryConditionSpec::Kind::Rotation);
  EXPECT_EQ(again.boundary_conditions[0].angular_velocity, -0.25);
  EXPECT_EQ(again.boundary_conditions[0].centre, condition.centre);
}

TEST(CaseReaderRotation, ZeroRateIsRefusedAtItsValue) {
  const std::string text =
      kPlate +
      "boundary_conditions:\n"
      "  - {group: xmin, rotation: {angular_velocity: 0.0, centre: [0, 0.5]}}\n";
  expect_error(text, "boundary_conditions.0.rotation.angular_velocity", "0.0",
               "angular_velocity must be non-zero", "angular_velocity: 0.0");
}

TEST(CaseReaderRotation, BadValuesAreRefusedAtTheirKey) {
  const std::string head = kPlate + "boundary_conditions:\n  - {group: xmin, rotation: ";
  expect_error(head + "{angular_velocity: fast, centre: [0, 0.5]}}\n",
               "boundary_conditions.0.rotation.angular_velocity", "fast", "",
               "angular_velocity: fast");
  expect_error(head + "{angular_velocity: 1.0, centre: [0, 0.5, 1]}}\n",
               "boundary_conditions.0.rotation.centre", "[0, 0.5, 1]", "3 components",
               "centre: [0, 0.5, 1]");
  expect_error(head + "{angular_velocity: 1.0}}\n", "boundary_conditions.0.rotation.centre", "", "",
               "rotation:");
  expect_error(head + "{angular_velocity: 1.0, center: [0, 0]}}\n",
               "boundary_conditions.0.rotation.center", "", "", "center:");
  // One kind per condition.
  expect_error(kPlate +
                   "boundary_conditions:\n  - {group: xmin, fixed: true, rotation: "
                   "{angular_velocity: 1.0, centre: [0, 0]}}\n",
               "boundary_conditions.0.rotation", "", "", "rotation:");
}

TEST(CaseReaderRotation, OneDimensionalCaseIsRefused) {
  const std::string text = kBar +
                           "boundary_conditions:\n"
                           "  - {group: xmin, rotation: {angular_velocity: 1.0, centre: 0}}\n";
  expect_error(text, "boundary_conditions.0.rotation", "", "only allowed in 2D", "rotation:");
}

// ---------------------------------------------------------------------------------------------
// initial_conditions.stress

TEST(CaseReaderInitialStress, ReadsComponentsWithTheirLinesAndWritesThemBack) {
  const std::string text = kPlate +
                           "initial_conditions:\n"
                           "  stress:\n"
                           "    xx: -1000.0\n"
                           "    xy: 250.0\n"
                           "    zz: -300.0\n";
  const CaseDescription description = read_case_text(text, kFile);
  const auto& stress = description.initial.stress;
  ASSERT_EQ(stress.size(), 3u);
  EXPECT_EQ(stress.at("xx").value, -1000.0);
  EXPECT_EQ(stress.at("xy").value, 250.0);
  EXPECT_EQ(stress.at("zz").value, -300.0);
  EXPECT_EQ(stress.at("xy").where.line, test::line_of(text, "xy: 250.0"));
  const CaseDescription again = reread(description);
  ASSERT_EQ(again.initial.stress.size(), 3u);
  for (const auto& [component, parameter] : stress)
    EXPECT_EQ(again.initial.stress.at(component).value, parameter.value) << component;
}

TEST(CaseReaderInitialStress, BadValuesAreRefusedAtTheirKey) {
  const std::string head = kPlate + "initial_conditions:\n  stress: ";
  expect_error(head + "{xx: -1000.0, yx: 5.0}\n", "initial_conditions.stress.yx", "", "",
               "yx: 5.0");
  expect_error(head + "{xx: lots}\n", "initial_conditions.stress.xx", "lots", "", "xx: lots");
  expect_error(head + "{}\n", "initial_conditions.stress", "", "no component", "stress:");
  expect_error(head + "-1000.0\n", "initial_conditions.stress", "-1000.0", "", "stress:");
}

// ---------------------------------------------------------------------------------------------
// initial_conditions.angular_velocity

TEST(CaseReaderInitialRotation, ReadsRateAndCentreAndWritesThemBack) {
  const std::string text =
      kPlate + "initial_conditions:\n  angular_velocity: {rate: 2.0, centre: [2, 0.5]}\n";
  const CaseDescription description = read_case_text(text, kFile);
  ASSERT_TRUE(description.initial.angular_velocity.has_value());
  EXPECT_EQ(description.initial.angular_velocity->rate, 2.0);
  EXPECT_EQ(description.initial.angular_velocity->centre, (Vec3{2.0, 0.5, 0.0}));
  EXPECT_EQ(description.initial.angular_velocity->where.line,
            test::line_of(text, "angular_velocity:"));
  const CaseDescription again = reread(description);
  ASSERT_TRUE(again.initial.angular_velocity.has_value());
  EXPECT_EQ(again.initial.angular_velocity->rate, 2.0);
  EXPECT_EQ(again.initial.angular_velocity->centre, (Vec3{2.0, 0.5, 0.0}));
}

TEST(CaseReaderInitialRotation, BadValuesAreRefusedAtTheirKey) {
  const std::string head = kPlate + "initial_conditions:\n  angular_velocity: ";
  expect_error(head + "{rate: quick, centre: [0, 0]}\n", "initial_conditions.angular_velocity.rate",
               "quick", "", "rate: quick");
  expect_error(head + "{rate: 1.0}\n", "initial_conditions.angular_velocity.centre", "", "",
               "angular_velocity:");
  expect_error(head + "{rate: 1.0, centre: [0]}\n", "initial_conditions.angular_velocity.centre",
               "[0]", "1 components", "centre: [0]");
}

TEST(CaseReaderInitialRotation, OneDimensionalCaseIsRefused) {
  const std::string text =
      kBar + "initial_conditions:\n  angular_velocity: {rate: 1.0, centre: 0}\n";
  expect_error(text, "initial_conditions.angular_velocity", "", "only allowed in 2D",
               "angular_velocity:");
}

// ---------------------------------------------------------------------------------------------
// initial_conditions.bending_mode

TEST(CaseReaderBendingMode, ReadsItsKeysAndWritesThemBack) {
  const std::string text = kPlate +
                           "initial_conditions:\n"
                           "  bending_mode: {root: 0.5, length: 3.5, tip_velocity: -0.01}\n";
  const CaseDescription description = read_case_text(text, kFile);
  ASSERT_TRUE(description.initial.bending_mode.has_value());
  EXPECT_EQ(description.initial.bending_mode->root, 0.5);
  EXPECT_EQ(description.initial.bending_mode->length, 3.5);
  EXPECT_EQ(description.initial.bending_mode->tip_velocity, -0.01);
  const CaseDescription again = reread(description);
  ASSERT_TRUE(again.initial.bending_mode.has_value());
  EXPECT_EQ(again.initial.bending_mode->root, 0.5);
  EXPECT_EQ(again.initial.bending_mode->length, 3.5);
  EXPECT_EQ(again.initial.bending_mode->tip_velocity, -0.01);
}

TEST(CaseReaderBendingMode, BadValuesAreRefusedAtTheirKey) {
  const std::string head = kPlate + "initial_conditions:\n  bending_mode: ";
  expect_error(head + "{root: 0, length: -1.0, tip_velocity: 0.01}\n",
               "initial_conditions.bending_mode.length", "-1.0", "", "length: -1.0");
  expect_error(head + "{root: 0, length: 0, tip_velocity: 0.01}\n",
               "initial_conditions.bending_mode.length", "0", "", "length: 0");
  expect_error(head + "{root: 0, tip_velocity: 0.01}\n", "initial_conditions.bending_mode.length",
               "", "", "bending_mode:");
  expect_error(head + "{root: 0, length: 1, tip_velocity: 0.01, tip: 1}\n",
               "initial_conditions.bending_mode.tip", "", "", "tip: 1");
}

TEST(CaseReaderBendingMode, OneDimensionalCaseIsRefused) {
  const std::string text =
      kBar + "initial_conditions:\n  bending_mode: {root: 0, length: 1, tip_velocity: 0.01}\n";
  expect_error(text, "initial_conditions.bending_mode", "", "only allowed in 2D", "bending_mode:");
}

}  // namespace
}  // namespace rktsph::motion_input_test
