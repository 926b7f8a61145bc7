// The frictional materials built by name through create_material, their defaults (F0 and the
// matching), and the located InputError for out-of-range angles, an unknown matching word, a
// number given for a word and a cohesionless soil without a reference stress
// (docs/input-reference.md, materials).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/materials/material_factory.hpp"
#include "rktsph/materials/perzyna_drucker_prager.hpp"
#include "rktsph/materials/perzyna_mohr_coulomb.hpp"

namespace rktsph::frictional_factory_test {
namespace {

SourceLocation at_line(int line) {
  return SourceLocation{"case.yaml", line, 5};
}

ParameterBlock frictional_block(const std::string& model) {
  ParameterBlock block;
  block.path = "materials.sand";
  block.where = at_line(10);
  block.words["model"] = {model, at_line(11)};
  block.values["density"] = {1900.0, at_line(12)};
  block.values["young_modulus"] = {20e6, at_line(13)};
  block.values["poisson_ratio"] = {0.3, at_line(14)};
  block.values["cohesion"] = {5e3, at_line(15)};
  block.values["friction_angle"] = {30.0, at_line(16)};
  block.values["fluidity"] = {10.0, at_line(17)};
  return block;
}

InputError error_of(const ParameterBlock& block) {
  try {
    create_material(block);
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "no InputError for " << block.path;
  return InputError({}, "", "", "", "");
}

double sine(double degrees) {
  return std::sin(degrees * std::numbers::pi / 180.0);
}

TEST(FrictionalFactory, BuildsDruckerPragerWithDefaults) {
  const auto material = create_material(frictional_block("perzyna_drucker_prager"));
  ASSERT_EQ(material->model_name(), "perzyna_drucker_prager");
  EXPECT_EQ(material->internal_names(),
            (std::vector<std::string>{"eps_vp", "cohesion", "friction_angle"}));
  const auto* dp = dynamic_cast<const PerzynaDruckerPrager*>(material.get());
  ASSERT_NE(dp, nullptr);
  EXPECT_EQ(dp->parameters().matching, ConeMatching::PlaneStrain);
  const FrictionalParameters& p = dp->parameters().strength;
  EXPECT_EQ(p.dilatancy_angle, 0.0);
  EXPECT_EQ(p.exponent, 1.0);
  EXPECT_EQ(p.tension_cutoff, std::numeric_limits<double>::infinity());
  // F0 = k of the plane-strain cone at psi = 0: sqrt3 c cos(phi) (docs/theory.md eq. 1.12).
  EXPECT_NEAR(p.reference_stress, std::sqrt(3.0) * 5e3 * std::cos(std::numbers::pi / 6.0), 1e-9);
  std::vector<double> internal(3);
  material->initial_internal(internal);
  EXPECT_EQ(internal, (std::vector<double>{0.0, 5e3, 30.0}));
  // No instant cut-off (§1.7): the cut-off is a viscoplastic surface of the material.
  EXPECT_EQ(material->tension_cutoff(), std::numeric_limits<double>::infinity());
}

TEST(FrictionalFactory, MatchingWordSelectsTheCone) {
  ParameterBlock block = frictional_block("perzyna_drucker_prager");
  block.words["matching"] = {"compression", at_line(18)};
  const auto material = create_material(block);
  const auto* dp = dynamic_cast<const PerzynaDruckerPrager*>(material.get());
  ASSERT_NE(dp, nullptr);
  EXPECT_EQ(dp->parameters().matching, ConeMatching::Compression);
  // F0 = 6 c cos(phi) / (3 - sin phi).
  EXPECT_NEAR(dp->parameters().strength.reference_stress,
              6.0 * 5e3 * std::cos(std::numbers::pi / 6.0) / (3.0 - sine(30.0)), 1e-9);

  block.words["matching"] = {"triaxial", at_line(18)};
  InputError error = error_of(block);
  EXPECT_EQ(error.key(), "materials.sand.matching");
  EXPECT_EQ(error.location().line, 18);
  EXPECT_NE(error.allowed().find("plane_strain"), std::string::npos);

  block.words.erase("matching");
  block.values["matching"] = {1.0, at_line(19)};
  error = error_of(block);
  EXPECT_EQ(error.key(), "materials.sand.matching");
  EXPECT_EQ(error.location().line, 19);
}

TEST(FrictionalFactory, WordForANumberIsAnError) {
  ParameterBlock block = frictional_block("perzyna_mohr_coulomb");
  block.values.erase("cohesion");
  block.words["cohesion"] = {"high", at_line(15)};
  const InputError error = error_of(block);
  EXPECT_EQ(error.key(), "materials.sand.cohesion");
  EXPECT_EQ(error.location().line, 15);
  EXPECT_NE(error.problem().find("number"), std::string::npos);
}

TEST(FrictionalFactory, BuildsMohrCoulombWithDefaults) {
  const auto material = create_material(frictional_block("perzyna_mohr_coulomb"));
  ASSERT_EQ(material->model_name(), "perzyna_mohr_coulomb");
  const auto* mc = dynamic_cast<const PerzynaMohrCoulomb*>(material.get());
  ASSERT_NE(mc, nullptr);
  EXPECT_NEAR(mc->parameters().reference_stress, 5e3 * std::cos(std::numbers::pi / 6.0), 1e-9);
  // The matching belongs to the cone only.
  ParameterBlock block = frictional_block("perzyna_mohr_coulomb");
  block.words["matching"] = {"compression", at_line(18)};
  EXPECT_EQ(error_of(block).key(), "materials.sand.matching");
}

TEST(FrictionalFactory, OutOfRangeValuesNameTheirKey) {
  for (const std::string model : {"perzyna_drucker_prager", "perzyna_mohr_coulomb"}) {
    ParameterBlock block = frictional_block(model);
    block.values["dilatancy_angle"] = {35.0, at_line(20)};  // above phi = 30
    InputError error = error_of(block);
    EXPECT_EQ(error.key(), "materials.sand.dilatancy_angle") << model;
    EXPECT_EQ(error.location().line, 20);
    EXPECT_NE(error.allowed().find("30]"), std::string::npos) << error.allowed();

    block = frictional_block(model);
    block.values["friction_angle"] = {90.0, at_line(16)};  // above 89
    EXPECT_EQ(error_of(block).key(), "materials.sand.friction_angle") << model;

    block = frictional_block(model);
    block.values["minimum_cohesion"] = {6e3, at_line(21)};  // above c0
    EXPECT_EQ(error_of(block).key(), "materials.sand.minimum_cohesion") << model;

    // Cohesionless: phi must be > 0, and F0 has no default.
    block = frictional_block(model);
    block.values["cohesion"] = {0.0, at_line(15)};
    error = error_of(block);
    EXPECT_EQ(error.key(), "materials.sand.reference_stress") << model;
    EXPECT_EQ(error.problem(), "missing required key");
    block.values["reference_stress"] = {10e3, at_line(22)};
    EXPECT_NO_THROW(create_material(block));
    block.values["friction_angle"] = {0.0, at_line(16)};
    EXPECT_EQ(error_of(block).key(), "materials.sand.friction_angle") << model;

    block = frictional_block(model);
    block.values["tension_cutoff"] = {-1.0, at_line(23)};
    EXPECT_EQ(error_of(block).key(), "materials.sand.tension_cutoff") << model;
  }
}

/// The smallest 1D case of tests/data/cases with `soil` made a frictional material whose
/// `matching` line is `matching_line`.
std::string case_text(const std::string& matching_line) {
  const auto path = std::filesystem::path(__FILE__).parent_path().parent_path() / "data" / "cases" /
                    "bar1d_minimal.yaml";
  std::ifstream stream(path);
  std::ostringstream text;
  text << stream.rdbuf();
  std::string contents = text.str();
  const std::string from = "    model: linear_elastic\n";
  const std::size_t at = contents.find(from);
  EXPECT_NE(at, std::string::npos) << "fixture lacks the linear_elastic soil";
  if (at == std::string::npos) return contents;
  return contents.replace(at, from.size(),
                          "    model: perzyna_drucker_prager\n    cohesion: 5.0e3\n"
                          "    friction_angle: 30\n    fluidity: 10\n" +
                              matching_line);
}

TEST(FrictionalFactory, CaseReaderKeepsTheMatchingWord) {
  // The case reader stores the word of `matching` for the material to check
  // (materials_section.cpp); it survives writing the resolved case and reading it again.
  const CaseDescription description =
      read_case_text(case_text("    matching: extension\n"), "case.yaml");
  const ParameterBlock& soil = description.materials.at("soil");
  ASSERT_EQ(soil.words.count("matching"), 1u);
  EXPECT_EQ(soil.words.at("matching").first, "extension");
  EXPECT_EQ(soil.words.at("matching").second.line, 15);
  const auto material = create_material(soil);
  const auto* dp = dynamic_cast<const PerzynaDruckerPrager*>(material.get());
  ASSERT_NE(dp, nullptr);
  EXPECT_EQ(dp->parameters().matching, ConeMatching::Extension);
  const CaseDescription again = read_case_text(write_case_yaml(description), "resolved.yaml");
  EXPECT_EQ(again.materials.at("soil").words.at("matching").first, "extension");

  // Not a name, or not one of the matchings: an error at the key.
  for (const std::string value : {"Extension", "[extension]", "triaxial", "2"}) {
    try {
      const CaseDescription bad =
          read_case_text(case_text("    matching: " + value + "\n"), "case.yaml");
      create_material(bad.materials.at("soil"));
      ADD_FAILURE() << "no InputError for matching: " << value;
    } catch (const InputError& error) {
      EXPECT_EQ(error.key(), "materials.soil.matching") << value;
    }
  }
}

}  // namespace
}  // namespace rktsph::frictional_factory_test
