// The single-point driver: mixed strain/stress control against closed-form linear elasticity,
// time-dependent rates, the sub-step rule of docs/theory.md eq. 2.7, recording, and its errors.
#include "rktsph/materials/point_driver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "rktsph/core/error.hpp"
#include "rktsph/materials/linear_elastic.hpp"
#include "rktsph/materials/perzyna_von_mises.hpp"

namespace rktsph::point_driver_test {
namespace {

ElasticConstants elasticity() {
  ElasticConstants elastic;
  elastic.young_modulus = 30e6;
  elastic.poisson_ratio = 0.25;
  return elastic;
}

TEST(PointDriver, UniaxialStressOfElasticBarIsYoungModulusTimesStrain) {
  const LinearElastic material(2000.0, elasticity());
  DriveOptions options;
  options.time_step = 0.1;
  const auto history = drive(material, StrainPath::uniaxial_stress(1e-3, 1.0),
                             initial_point_state(material, {}), options);
  const PointState& last = history.back();
  // Hooke's law in uniaxial stress: sigma = E eps, lateral strain -nu eps. The rates are
  // constant, so RK4 is exact up to round-off (1e-16 relative per operation).
  EXPECT_NEAR(last.time, 1.0, 1e-15);
  EXPECT_NEAR(last.strain[0], 1e-3, 1e-15);
  EXPECT_NEAR(last.stress[0], 30e6 * 1e-3, 1e-8);
  EXPECT_NEAR(last.stress[1], 0.0, 1e-8);
  EXPECT_NEAR(last.stress[2], 0.0, 1e-8);
  EXPECT_NEAR(last.strain[1], -0.25e-3, 1e-15);
  EXPECT_NEAR(last.strain[2], -0.25e-3, 1e-15);
}

TEST(PointDriver, ConfinedCompressionUsesConstrainedModulus) {
  const LinearElastic material(2000.0, elasticity());
  DriveOptions options;
  options.time_step = 0.25;
  const auto history =
      drive(material, StrainPath::constant_strain_rate({-2e-3, 0, 0, 0, 0, 0}, 1.0),
            initial_point_state(material, {}), options);
  // Oedometer: sigma_xx = (lambda + 2G) eps, sigma_yy = sigma_zz = lambda eps with
  // lambda = E nu/((1+nu)(1-2nu)) = 12 MPa and G = E/(2(1+nu)) = 12 MPa here.
  const double lambda = 30e6 * 0.25 / (1.25 * 0.5), shear = 30e6 / 2.5;
  EXPECT_NEAR(history.back().stress[0], (lambda + 2.0 * shear) * -2e-3, 1e-7);
  EXPECT_NEAR(history.back().stress[1], lambda * -2e-3, 1e-7);
}

TEST(PointDriver, SimpleShearAndTimeDependentRate) {
  const LinearElastic material(2000.0, elasticity());
  StrainPath path;
  // Tensor shear strain e_xy = 1e-3 sin(t): its rate 1e-3 cos(t).
  path.rate = [](double time) { return SymmetricTensor{0, 0, 0, 1e-3 * std::cos(time), 0, 0}; };
  path.duration = 1.0;
  DriveOptions options;
  options.time_step = 0.05;
  const auto history = drive(material, path, initial_point_state(material, {}), options);
  // sigma_xy = 2 G e_xy. RK4 integrates cos over 20 steps of 0.05 to ~h^4/180 * 1e-3 ~ 3.5e-11.
  const double expected_strain = 1e-3 * std::sin(1.0);
  EXPECT_NEAR(history.back().strain[3], expected_strain, 1e-10);
  EXPECT_NEAR(history.back().stress[3], 2.0 * 12e6 * expected_strain, 12e6 * 2e-10);
}

TEST(PointDriver, SubstepsFollowSourceStiffnessRule) {
  PerzynaVonMisesParameters parameters;
  parameters.yield_stress = 100e3;
  parameters.fluidity = 2.0;
  parameters.minimum_yield_stress = 1e3;
  const PerzynaVonMises material(2000.0, elasticity(), parameters);
  // N = 1: stiffness 3 G gamma / Y = 3 * 12e6 * 2 / 1e5 = 720 1/s; dt = 0.01 s gives
  // ceil(0.01 * 720 / 2.5) = ceil(2.88) = 3 sub-steps.
  DriveOptions options;
  options.time_step = 0.01;
  options.record_every = 3;
  const auto history = drive(material, StrainPath::uniaxial_stress(1e-3, 0.105),
                             initial_point_state(material, {}), options);
  // 11 steps (the last one 0.005 s: ceil(1.44) = 2); kept: start, steps 3, 6, 9 and the last.
  ASSERT_EQ(history.size(), 5u);
  EXPECT_EQ(history[0].substeps, 0);
  EXPECT_EQ(history[1].substeps, 3);
  EXPECT_NEAR(history[1].time, 0.03, 1e-15);
  EXPECT_NEAR(history.back().time, 0.105, 1e-15);
  EXPECT_EQ(history.back().substeps, 2);

  options.max_substeps = 2;
  EXPECT_EQ(drive(material, StrainPath::uniaxial_stress(1e-3, 0.01),
                  initial_point_state(material, {}), options)
                .back()
                .substeps,
            2);
}

TEST(PointDriver, DivergenceIsARunError) {
  // One RK4 step of z = dt * 3 G gamma / Y = 7200 per step grows the overstress by ~z^4/24.
  PerzynaVonMisesParameters parameters;
  parameters.yield_stress = 100e3;
  parameters.fluidity = 2e4;
  parameters.minimum_yield_stress = 1e3;
  const PerzynaVonMises material(2000.0, elasticity(), parameters);
  DriveOptions options;
  options.time_step = 1e-3;
  options.max_substeps = 1;
  EXPECT_THROW(drive(material, StrainPath::uniaxial_stress(0.0, 1.0),
                     initial_point_state(material, {2e5, 0, 0, 0, 0, 0}), options),
               RunError);
}

TEST(PointDriver, RejectsBadOptions) {
  const LinearElastic material(2000.0, elasticity());
  DriveOptions options;  // time_step = 0
  EXPECT_THROW(drive(material, StrainPath::uniaxial_stress(1e-3, 1.0),
                     initial_point_state(material, {}), options),
               std::invalid_argument);
  options.time_step = 0.1;
  StrainPath no_rate;
  no_rate.duration = 1.0;
  EXPECT_THROW(drive(material, no_rate, initial_point_state(material, {}), options),
               std::invalid_argument);
}

}  // namespace
}  // namespace rktsph::point_driver_test
