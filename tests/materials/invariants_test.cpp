// Stress invariants, Lode angle and the invariant gradients m1, m2, m3 (docs/theory.md
// eqs. 1.6–1.7) against eigenvalue-based invariants (Eigen), physical load cases and central finite
// differences.
#include "rktsph/materials/invariants.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "stress_states.hpp"

namespace rktsph::invariants_test {
namespace {

using test_support::distance;
using test_support::finite_difference_gradient;
using test_support::principal_invariants;
using test_support::random_rotation;
using test_support::rotated_principal;
using test_support::tensor_norm;
using test_support::to_matrix;

constexpr double kPi = std::numbers::pi;
// asin is ill-conditioned at +-1: a sin 3theta that is 1 - 1e-15 after round-off gives
// 3 theta = pi/2 - sqrt(2e-15) = pi/2 - 4.5e-8, so theta is checked to 1e-7 rad there.
constexpr double kLodeTolerance = 1e-7;

TEST(Invariants, MatchEigenvalueInvariantsOfRotatedStates) {
  std::mt19937 generator(11);
  std::uniform_real_distribution<double> principal(-4e5, 1e5);
  for (int sample = 0; sample < 20; ++sample) {
    const SymmetricTensor stress =
        rotated_principal({principal(generator), principal(generator), principal(generator)},
                          random_rotation(generator));
    const StressInvariants invariants = stress_invariants(stress);
    const auto reference = principal_invariants(stress);
    // Both sides are sums of a few products of O(4e5) numbers: round-off ~1e-15 of the scale;
    // the eigen-solver is accurate to ~1e-14 relative, so 1e-10 of the scale is ample.
    const double scale = 4e5;
    EXPECT_NEAR(invariants.pressure, reference.pressure, 1e-10 * scale);
    EXPECT_NEAR(invariants.j2, reference.j2, 1e-10 * scale * scale);
    EXPECT_NEAR(invariants.j3, reference.j3, 1e-10 * scale * scale * scale);
    EXPECT_NEAR(invariants.q, reference.q, 1e-10 * scale);
    EXPECT_NEAR(invariants.sin_3theta, reference.sin_3theta, 1e-8);
    EXPECT_TRUE(invariants.lode_defined);
  }
}

TEST(Invariants, TriaxialCompressionGivesPlus30Degrees) {
  // Tension positive: the axial stress is the most compressive, the two radial ones are equal.
  const SymmetricTensor stress = {-300e3, -100e3, -100e3, 0.0, 0.0, 0.0};
  const StressInvariants invariants = stress_invariants(stress);
  EXPECT_NEAR(invariants.lode_angle, kPi / 6.0, kLodeTolerance);
  EXPECT_NEAR(invariants.pressure, 500e3 / 3.0, 1e-9);
  EXPECT_NEAR(invariants.q, 200e3, 1e-9);
  // Same state with the axis along y and a rotated frame.
  std::mt19937 generator(3);
  EXPECT_NEAR(
      stress_invariants(rotated_principal({-100e3, -300e3, -100e3}, random_rotation(generator)))
          .lode_angle,
      kPi / 6.0, kLodeTolerance);
}

TEST(Invariants, TriaxialExtensionGivesMinus30Degrees) {
  // The axial stress is the least compressive; uniaxial tension is of the same kind.
  EXPECT_NEAR(stress_invariants({-100e3, -300e3, -300e3, 0.0, 0.0, 0.0}).lode_angle, -kPi / 6.0,
              kLodeTolerance);
  EXPECT_NEAR(stress_invariants({50e3, 0.0, 0.0, 0.0, 0.0, 0.0}).lode_angle, -kPi / 6.0,
              kLodeTolerance);
}

TEST(Invariants, PureShearGivesZeroLodeAngle) {
  const StressInvariants shear = stress_invariants({0.0, 0.0, 0.0, 70e3, 0.0, 0.0});
  EXPECT_NEAR(shear.lode_angle, 0.0, 1e-12);
  EXPECT_NEAR(shear.j2, 70e3 * 70e3, 1e-6);
  // Principal (a, 0, -a) about a pressure is the same deviatoric state.
  EXPECT_NEAR(stress_invariants({-50e3, -150e3, -250e3, 0.0, 0.0, 0.0}).lode_angle, 0.0, 1e-12);
}

TEST(Invariants, HydrostaticStateHasNoLodeAngle) {
  const StressInvariants invariants = stress_invariants({-1e5, -1e5, -1e5, 0.0, 0.0, 0.0});
  EXPECT_FALSE(invariants.lode_defined);
  EXPECT_EQ(invariants.lode_angle, 0.0);
  EXPECT_EQ(invariants.sin_3theta, 0.0);
  EXPECT_EQ(invariants.j2, 0.0);
}

TEST(Invariants, SquareAndDeterminantMatchMatrixAlgebra) {
  std::mt19937 generator(5);
  std::uniform_real_distribution<double> component(-2.0, 2.0);
  for (int sample = 0; sample < 10; ++sample) {
    SymmetricTensor tensor;
    for (double& c : tensor)
      c = component(generator);
    const Eigen::Matrix3d matrix = to_matrix(tensor);
    // O(1) entries: products accurate to a few ulps.
    EXPECT_LT(distance(square(tensor), test_support::to_tensor(matrix * matrix)), 1e-13);
    EXPECT_NEAR(determinant(tensor), matrix.determinant(), 1e-13);
  }
}

TEST(Invariants, GradientsMatchFiniteDifferences) {
  std::mt19937 generator(17);
  std::uniform_real_distribution<double> principal(-3e5, 1e5);
  const auto i1 = [](const SymmetricTensor& s) { return s[0] + s[1] + s[2]; };
  const auto root_j2 = [](const SymmetricTensor& s) {
    return std::sqrt(principal_invariants(s).j2);
  };
  const auto j3 = [](const SymmetricTensor& s) { return principal_invariants(s).j3; };
  for (int sample = 0; sample < 10; ++sample) {
    const SymmetricTensor stress =
        rotated_principal({principal(generator), principal(generator), principal(generator)},
                          random_rotation(generator));
    const StressInvariants invariants = stress_invariants(stress);
    // Step 1 Pa on a 1e5 Pa scale: truncation (step/scale)^2 = 1e-10, round-off of the
    // eigenvalues 1e-15 * scale^k / step relative to a gradient of size scale^(k-1): 1e-10.
    const double step = 1.0;
    const SymmetricTensor m1 = gradient_of_i1();
    const SymmetricTensor m2 = gradient_of_sqrt_j2(invariants);
    const SymmetricTensor m3 = gradient_of_j3(invariants);
    EXPECT_LT(distance(m1, finite_difference_gradient(i1, stress, step)), 1e-6 * tensor_norm(m1));
    EXPECT_LT(distance(m2, finite_difference_gradient(root_j2, stress, step)),
              1e-6 * tensor_norm(m2));
    EXPECT_LT(distance(m3, finite_difference_gradient(j3, stress, step)), 1e-6 * tensor_norm(m3));
  }
}

TEST(Invariants, EquivalentStrainRateOfSimpleRates) {
  // Isochoric uniaxial rate (1, -1/2, -1/2): sqrt(2/3 (1 + 1/4 + 1/4)) = 1.
  EXPECT_NEAR(equivalent_strain_rate({1.0, -0.5, -0.5, 0.0, 0.0, 0.0}), 1.0, 1e-15);
  // A volumetric rate has no deviatoric part.
  EXPECT_NEAR(equivalent_strain_rate({2.0, 2.0, 2.0, 0.0, 0.0, 0.0}), 0.0, 1e-15);
  // Simple shear with engineering rate g (tensor component g/2): sqrt(2/3 * 2 g^2/4) = g/sqrt3.
  EXPECT_NEAR(equivalent_strain_rate({0.0, 0.0, 0.0, 0.5 * 0.3, 0.0, 0.0}), 0.3 / std::sqrt(3.0),
              1e-15);
}

TEST(Invariants, ElasticStiffnessMatchesEngineeringForm) {
  ElasticConstants elastic;
  elastic.young_modulus = 20e6;
  elastic.poisson_ratio = 0.3;
  const double e = elastic.young_modulus, nu = elastic.poisson_ratio;
  // Uniaxial strain: sigma_xx = E (1 - nu) / ((1 + nu)(1 - 2 nu)), lateral E nu / (...).
  const double denominator = (1.0 + nu) * (1.0 - 2.0 * nu);
  const SymmetricTensor stress = apply_elastic_stiffness(elastic, {1e-3, 0, 0, 0, 0, 0});
  EXPECT_NEAR(stress[0], e * (1.0 - nu) / denominator * 1e-3, 1e-6);
  EXPECT_NEAR(stress[1], e * nu / denominator * 1e-3, 1e-6);
  EXPECT_NEAR(stress[2], e * nu / denominator * 1e-3, 1e-6);
  // Tensor shear strain e_xy gives sigma_xy = 2 G e_xy = E/(1 + nu) e_xy.
  EXPECT_NEAR(apply_elastic_stiffness(elastic, {0, 0, 0, 0, 0, 1e-3})[5], e / (1.0 + nu) * 1e-3,
              1e-6);
}

}  // namespace
}  // namespace rktsph::invariants_test
