// Strength reduction (docs/theory.md §10): the reduced strengths of eq. 10.1 computed by hand, and
// the input errors for the cases it cannot treat.
#include "rktsph/strength_reduction/strength_reduction.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/error.hpp"

namespace rktsph::strength_reduction_test {
namespace {

std::string slope_case(const std::string& material) {
  return R"(name: fos-test
dimension: 2
plane: strain
geometry:
  spacing: 1.0
  shapes:
    - rectangle: {min: [0, 0], max: [6, 3]}
      material: soil
    - rectangle: {min: [0, -2], max: [6, 0]}
      material: base
materials:
  soil:
)" + material +
         R"(
  base: {model: linear_elastic, density: 2000, young_modulus: 1.0e8, poisson_ratio: 0.3}
boundary_conditions:
  - {group: ymin, fixed: true}
loads:
  gravity: {acceleration: [0, -9.81], factor: {function: ramp, value: 1, duration: 1.0}}
  damping: {coefficient: 10}
time:
  end: 3.0
)";
}

const std::string kDruckerPrager =
    "    {model: perzyna_drucker_prager, density: 2000, young_modulus: 2.0e7, poisson_ratio: 0.3, "
    "cohesion: 1.0e4, friction_angle: 30, dilatancy_angle: 25, minimum_cohesion: 2.0e3, "
    "fluidity: 1.0}";

double parameter(const CaseDescription& description, const std::string& material,
                 const std::string& key) {
  return description.materials.at(material).values.at(key).value;
}

TEST(StrengthReduction, DividesCohesionAndTangentOfFriction) {
  const CaseDescription description = read_case_text(slope_case(kDruckerPrager), "fos.yaml");
  const double factor = 1.5;
  const CaseDescription reduced = reduce_strength(description, factor);
  const double degree = std::numbers::pi / 180.0;
  EXPECT_DOUBLE_EQ(parameter(reduced, "soil", "cohesion"), 1.0e4 / 1.5);
  EXPECT_DOUBLE_EQ(parameter(reduced, "soil", "minimum_cohesion"), 2.0e3 / 1.5);
  // tan phi_F = tan 30 deg / 1.5 = 0.3849: phi_F = 21.05 deg.
  const double phi = parameter(reduced, "soil", "friction_angle");
  EXPECT_NEAR(std::tan(phi * degree), std::tan(30.0 * degree) / factor, 1e-14);
  EXPECT_NEAR(phi, 21.0517, 1e-4);
  // psi = 25 deg is above phi_F: lowered to it (psi <= phi).
  EXPECT_DOUBLE_EQ(parameter(reduced, "soil", "dilatancy_angle"), phi);
  // The elastic base and every elastic constant are kept.
  EXPECT_DOUBLE_EQ(parameter(reduced, "soil", "young_modulus"), 2.0e7);
  EXPECT_DOUBLE_EQ(parameter(reduced, "base", "young_modulus"), 1.0e8);
  // At F = 1.1 psi = 25 deg stays below phi_F = 27.7 deg.
  EXPECT_DOUBLE_EQ(parameter(reduce_strength(description, 1.1), "soil", "dilatancy_angle"), 25.0);
}

TEST(StrengthReduction, DividesTheVonMisesYieldStress) {
  const CaseDescription description = read_case_text(
      slope_case("    {model: perzyna_von_mises, density: 2000, young_modulus: 2.0e7, "
                 "poisson_ratio: 0.3, yield_stress: 9.0e4, fluidity: 1.0}"),
      "fos.yaml");
  EXPECT_DOUBLE_EQ(parameter(reduce_strength(description, 1.2), "soil", "yield_stress"),
                   9.0e4 / 1.2);
}

TEST(StrengthReduction, ElasticReferenceKeepsDensityAndElasticity) {
  const CaseDescription elastic =
      elastic_reference(read_case_text(slope_case(kDruckerPrager), "fos.yaml"));
  const ParameterBlock& soil = elastic.materials.at("soil");
  EXPECT_EQ(soil.words.at("model").first, "linear_elastic");
  EXPECT_EQ(soil.values.size(), 3u);
  EXPECT_DOUBLE_EQ(soil.values.at("density").value, 2000.0);
}

std::string error_of(const std::string& text) {
  try {
    check_strength_reduction_case(read_case_text(text, "fos.yaml"));
  } catch (const InputError& error) {
    return error.what();
  }
  return {};
}

TEST(StrengthReduction, RefusesCasesWithoutAStrengthToReduce) {
  const std::string elastic = error_of(slope_case(
      "    {model: linear_elastic, density: 2000, young_modulus: 2.0e7, poisson_ratio: 0.3}"));
  EXPECT_NE(elastic.find("fos.yaml"), std::string::npos) << elastic;
  EXPECT_NE(elastic.find("no material has a strength to reduce"), std::string::npos) << elastic;
  EXPECT_NE(elastic.find("perzyna_drucker_prager"), std::string::npos) << elastic;
  const std::string cam_clay = error_of(
      slope_case("    {model: perzyna_modified_cam_clay, density: 2000, poisson_ratio: 0.3, "
                 "critical_state_ratio: 1.0, compression_index: 0.2, swelling_index: 0.04, "
                 "preconsolidation_pressure: 1.0e5, initial_void_ratio: 1.0, fluidity: 1.0}"));
  EXPECT_NE(cam_clay.find("materials.soil.model"), std::string::npos) << cam_clay;
  EXPECT_NE(cam_clay.find("perzyna_modified_cam_clay"), std::string::npos) << cam_clay;
}

std::string saturated_slope_case(double conductivity) {
  std::string text = slope_case(kDruckerPrager);
  text.insert(text.find("dimension"), "model: saturated_vpw\n");
  return text + "pore_fluid: {porosity: 0.3, bulk_modulus: 2.2e9, density: 1000, " +
         fmt::format("hydraulic_conductivity: {}}}\n", conductivity);
}

TEST(StrengthReduction, ASaturatedCaseMustDrainWithinItsTimeSpan) {
  // Eq. 10.3 by hand for the soil (the stiffer base consolidates faster): M = E (1 - nu) / ((1 +
  // nu)(1 - 2 nu)), c_v = k / (rho_w g) / (1 / M + n / K_w), over the body's height L = 5 m; the
  // case runs 3 s, so it must drain in 1.5 s.
  const double oedometric = 2.0e7 * 0.7 / (1.3 * 0.4);
  const auto drainage_time = [&](double conductivity) {
    const double coefficient = conductivity / (1000.0 * 9.81) / (1.0 / oedometric + 0.3 / 2.2e9);
    return 25.0 / coefficient;
  };
  const double enough = 2.0 * drainage_time(1.0) / 3.0;  // the least k that drains in time
  EXPECT_NO_THROW(check_strength_reduction_case(
      read_case_text(saturated_slope_case(1.02 * enough), "fos.yaml")));
  const std::string slow = error_of(saturated_slope_case(0.98 * enough));
  EXPECT_NE(slow.find("pore_fluid.hydraulic_conductivity"), std::string::npos) << slow;
  EXPECT_NE(slow.find("drained"), std::string::npos) << slow;
  EXPECT_NE(slow.find(fmt::format("{:.3g} m/s", enough)), std::string::npos) << slow;
  const std::string dry = error_of(saturated_slope_case(0.0));
  EXPECT_NE(dry.find("a conductivity > 0"), std::string::npos) << dry;
}

TEST(StrengthReduction, RefusesABadFactor) {
  const CaseDescription description = read_case_text(slope_case(kDruckerPrager), "fos.yaml");
  EXPECT_THROW(reduce_strength(description, 0.0), InputError);
  EXPECT_THROW(reduce_strength(description, -1.0), InputError);
}

}  // namespace
}  // namespace rktsph::strength_reduction_test
