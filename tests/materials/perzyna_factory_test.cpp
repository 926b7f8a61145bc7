// Both Perzyna materials built by name through create_material, with defaults, and the located
// InputError for missing, out-of-range and unknown keys (docs/input-reference.md, materials).
#include <gtest/gtest.h>

#include <limits>
#include <map>

#include <string>

#include "rktsph/core/error.hpp"
#include "rktsph/materials/material_factory.hpp"
#include "rktsph/materials/perzyna_modified_cam_clay.hpp"
#include "rktsph/materials/perzyna_von_mises.hpp"

namespace rktsph::perzyna_factory_test {
namespace {

SourceLocation at_line(int line) {
  return SourceLocation{"case.yaml", line, 5};
}

ParameterBlock von_mises_block() {
  ParameterBlock block;
  block.path = "materials.soil";
  block.where = at_line(10);
  block.words["model"] = {"perzyna_von_mises", at_line(11)};
  block.values["density"] = {2000.0, at_line(12)};
  block.values["young_modulus"] = {10e6, at_line(13)};
  block.values["poisson_ratio"] = {0.3, at_line(14)};
  block.values["yield_stress"] = {50e3, at_line(15)};
  block.values["fluidity"] = {4.0, at_line(16)};
  return block;
}

ParameterBlock cam_clay_block() {
  ParameterBlock block;
  block.path = "materials.clay";
  block.where = at_line(20);
  block.words["model"] = {"perzyna_modified_cam_clay", at_line(21)};
  block.values["density"] = {1800.0, at_line(22)};
  block.values["young_modulus"] = {8e6, at_line(23)};
  block.values["poisson_ratio"] = {0.25, at_line(24)};
  block.values["friction_angle"] = {25.0, at_line(25)};
  block.values["compression_index"] = {0.2, at_line(26)};
  block.values["swelling_index"] = {0.04, at_line(27)};
  block.values["initial_void_ratio"] = {0.9, at_line(28)};
  block.values["preconsolidation_pressure"] = {150e3, at_line(29)};
  block.values["fluidity"] = {0.5, at_line(30)};
  return block;
}

/// The InputError thrown by create_material, or a test failure if none is thrown.
InputError error_of(const ParameterBlock& block) {
  try {
    create_material(block);
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "no InputError for " << block.path;
  return InputError({}, "", "", "", "");
}

TEST(PerzynaFactory, BuildsVonMisesWithDefaults) {
  const auto material = create_material(von_mises_block());
  ASSERT_EQ(material->model_name(), "perzyna_von_mises");
  EXPECT_FALSE(material->is_elastic());
  EXPECT_EQ(material->internal_names(), (std::vector<std::string>{"eps_vp", "yield_stress"}));
  const auto* von_mises = dynamic_cast<const PerzynaVonMises*>(material.get());
  ASSERT_NE(von_mises, nullptr);
  // Defaults of the brief: H = 0, N = 1, minimum yield stress 1 % of Y0.
  EXPECT_EQ(von_mises->parameters().yield_stress, 50e3);
  EXPECT_EQ(von_mises->parameters().hardening_modulus, 0.0);
  EXPECT_EQ(von_mises->parameters().exponent, 1.0);
  EXPECT_EQ(von_mises->parameters().minimum_yield_stress, 500.0);
  EXPECT_EQ(von_mises->parameters().fluidity, 4.0);
  EXPECT_EQ(material->tension_cutoff(), std::numeric_limits<double>::infinity());  // off
  EXPECT_EQ(material->density(), 2000.0);
  std::vector<double> internal(2);
  material->initial_internal(internal);
  EXPECT_EQ(internal, (std::vector<double>{0.0, 50e3}));
}

TEST(PerzynaFactory, CamClayElasticityDefaultsToConstant) {
  const auto material = create_material(cam_clay_block());
  EXPECT_FALSE(material->stress_dependent_elasticity());
  EXPECT_EQ(material->elastic().young_modulus, 8e6);
  const SymmetricTensor stress{-50e3, -60e3, -70e3, 1e3, 0.0, 0.0};
  EXPECT_EQ(material->elastic_at(stress).young_modulus, 8e6);
  EXPECT_EQ(material->elastic_at(stress).poisson_ratio, 0.25);
}

/// The Cam-Clay block with pressure-dependent elasticity and G from nu (no young_modulus).
ParameterBlock pressure_dependent_block() {
  ParameterBlock block = cam_clay_block();
  block.values.erase("young_modulus");
  block.words["elasticity"] = {"pressure_dependent", at_line(31)};
  return block;
}

TEST(PerzynaFactory, CamClayPressureDependentElasticityKeys) {
  const auto material = create_material(pressure_dependent_block());
  ASSERT_TRUE(material->stress_dependent_elasticity());
  const auto& clay = dynamic_cast<const PerzynaModifiedCamClay&>(*material);
  // Defaults: the clamp [0.01 pc0, 4 pc0]; elastic() at 4 pc0, K = (1 + e0) p / kappa.
  EXPECT_DOUBLE_EQ(clay.parameters().minimum_pressure, 1.5e3);
  EXPECT_DOUBLE_EQ(clay.parameters().maximum_pressure, 600e3);
  EXPECT_NEAR(material->elastic().bulk_modulus(), 1.9 * 600e3 / 0.04, 1e-3);
  EXPECT_DOUBLE_EQ(material->elastic().poisson_ratio, 0.25);

  ParameterBlock with_shear = pressure_dependent_block();
  with_shear.values.erase("poisson_ratio");
  with_shear.values["shear_modulus"] = {3e6, at_line(32)};
  with_shear.values["minimum_pressure"] = {5e3, at_line(33)};
  with_shear.values["maximum_pressure"] = {400e3, at_line(34)};
  const auto constant_g = create_material(with_shear);
  EXPECT_NEAR(constant_g->elastic().shear_modulus(), 3e6, 1e-6);
  EXPECT_NEAR(constant_g->elastic().bulk_modulus(), 1.9 * 400e3 / 0.04, 1e-3);
}

TEST(PerzynaFactory, CamClayPressureDependentNeedsExactlyOneShearKey) {
  ParameterBlock both = pressure_dependent_block();
  both.values["shear_modulus"] = {3e6, at_line(32)};
  EXPECT_EQ(error_of(both).key(), "materials.clay");
  ParameterBlock neither = pressure_dependent_block();
  neither.values.erase("poisson_ratio");
  EXPECT_EQ(error_of(neither).key(), "materials.clay");
  // young_modulus is not a key of pressure-dependent elasticity: an unknown key at its line.
  ParameterBlock with_young = pressure_dependent_block();
  with_young.values["young_modulus"] = {8e6, at_line(35)};
  EXPECT_EQ(error_of(with_young).key(), "materials.clay.young_modulus");
  ParameterBlock unknown_word = cam_clay_block();
  unknown_word.words["elasticity"] = {"hyperelastic", at_line(31)};
  EXPECT_EQ(error_of(unknown_word).key(), "materials.clay.elasticity");
  // shear_modulus belongs to pressure-dependent elasticity only.
  ParameterBlock constant_with_shear = cam_clay_block();
  constant_with_shear.values["shear_modulus"] = {3e6, at_line(32)};
  EXPECT_EQ(error_of(constant_with_shear).key(), "materials.clay.shear_modulus");
}

TEST(PerzynaFactory, BuildsModifiedCamClay) {
  ParameterBlock block = cam_clay_block();
  block.values["exponent"] = {2.0, at_line(31)};
  const auto material = create_material(block);
  ASSERT_EQ(material->model_name(), "perzyna_modified_cam_clay");
  EXPECT_EQ(material->internal_names(),
            (std::vector<std::string>{"eps_vp", "preconsolidation_pressure"}));
  const auto* cam_clay = dynamic_cast<const PerzynaModifiedCamClay*>(material.get());
  ASSERT_NE(cam_clay, nullptr);
  EXPECT_EQ(cam_clay->parameters().exponent, 2.0);
  EXPECT_EQ(cam_clay->parameters().swelling_index, 0.04);
  // (1 + e0)/(lambda - kappa) = 1.9 / 0.16.
  EXPECT_NEAR(cam_clay->hardening_factor(), 1.9 / 0.16, 1e-12);
  std::vector<double> internal(2);
  material->initial_internal(internal);
  EXPECT_EQ(internal, (std::vector<double>{0.0, 150e3}));
}

TEST(PerzynaFactory, MissingKeyNamesItsPath) {
  ParameterBlock block = von_mises_block();
  block.values.erase("fluidity");
  const InputError error = error_of(block);
  EXPECT_EQ(error.key(), "materials.soil.fluidity");
  EXPECT_EQ(error.problem(), "missing required key");
  EXPECT_EQ(error.location().line, 10);  // the block, since the key is absent

  ParameterBlock clay = cam_clay_block();
  clay.values.erase("preconsolidation_pressure");
  EXPECT_EQ(error_of(clay).key(), "materials.clay.preconsolidation_pressure");
}

TEST(PerzynaFactory, OutOfRangeValuesNameTheirKeyAndLine) {
  ParameterBlock block = von_mises_block();
  block.values["exponent"] = {0.0, at_line(17)};  // N > 0
  InputError error = error_of(block);
  EXPECT_EQ(error.key(), "materials.soil.exponent");
  EXPECT_EQ(error.location().line, 17);

  block = von_mises_block();
  block.values["minimum_yield_stress"] = {60e3, at_line(18)};  // above Y0
  EXPECT_EQ(error_of(block).key(), "materials.soil.minimum_yield_stress");

  block = von_mises_block();
  block.values["tension_cutoff"] = {-1.0, at_line(19)};  // a cut-off in compression
  error = error_of(block);
  EXPECT_EQ(error.key(), "materials.soil.tension_cutoff");
  EXPECT_EQ(error.location().line, 19);
  block.values["tension_cutoff"] = {2e3, at_line(19)};
  EXPECT_EQ(create_material(block)->tension_cutoff(), 2e3);

  ParameterBlock clay = cam_clay_block();
  clay.values["compression_index"] = {0.03, at_line(26)};  // below kappa_c = 0.04
  error = error_of(clay);
  EXPECT_EQ(error.key(), "materials.clay.compression_index");
  EXPECT_EQ(error.location().line, 26);

  clay = cam_clay_block();
  clay.values["friction_angle"] = {90.0, at_line(25)};  // open interval (0, 90)
  EXPECT_EQ(error_of(clay).key(), "materials.clay.friction_angle");
}

TEST(PerzynaFactory, UnknownKeyIsRejected) {
  ParameterBlock block = cam_clay_block();
  block.values["hardening_modulus"] = {1e6, at_line(32)};  // a Von Mises key
  const InputError error = error_of(block);
  EXPECT_EQ(error.key(), "materials.clay.hardening_modulus");
  EXPECT_EQ(error.location().line, 32);
}

// A new user's block often has several mistakes; one run must list them all, as the rest of the
// case does, rather than one per attempt.
TEST(PerzynaFactory, EveryMistakeOfABlockIsReportedAtOnce) {
  ParameterBlock block = von_mises_block();
  block.values.erase("fluidity");
  block.values["exponent"] = {0.0, at_line(17)};
  block.values["poisson_ratio"] = {0.7, at_line(14)};
  const std::vector<InputError> errors = error_of(block).errors();
  ASSERT_EQ(errors.size(), 3u) << error_of(block).what();
  EXPECT_EQ(errors[0].key(), "materials.soil.fluidity");  // at the block's line, 10
  EXPECT_EQ(errors[1].key(), "materials.soil.poisson_ratio");
  EXPECT_EQ(errors[2].key(), "materials.soil.exponent");
}

TEST(PerzynaFactory, TheMistakesOfEveryBlockAreReportedTogether) {
  std::map<std::string, ParameterBlock> blocks;
  blocks["clay"] = cam_clay_block();
  blocks["clay"].values["friction_angle"] = {90.0, at_line(25)};
  blocks["soil"] = von_mises_block();
  blocks["soil"].values["fluidity"] = {-1.0, at_line(16)};
  try {
    create_materials(blocks);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    const std::vector<InputError> errors = error.errors();
    ASSERT_EQ(errors.size(), 2u) << error.what();
    EXPECT_EQ(errors[0].key(), "materials.soil.fluidity");  // line 16, before line 25
    EXPECT_EQ(errors[1].key(), "materials.clay.friction_angle");
  }
}

// "yeild_stress" is a typing slip for a known key: say which, both where the slip is written and
// where the key it was meant for is missing.
TEST(PerzynaFactory, AMisspeltKeyGetsASuggestion) {
  ParameterBlock block = von_mises_block();
  block.values.erase("yield_stress");
  block.values["yeild_stress"] = {50e3, at_line(15)};
  const InputError error = error_of(block);
  const std::string text = error.what();
  EXPECT_NE(text.find("materials.soil.yeild_stress"), std::string::npos) << text;
  EXPECT_NE(text.find("did you mean 'yield_stress'?"), std::string::npos) << text;
  EXPECT_NE(text.find("'yeild_stress' is written"), std::string::npos) << text;
}

}  // namespace
}  // namespace rktsph::perzyna_factory_test
