// Perzyna Modified Cam-Clay on a single material point (docs/theory.md §1.3, §1.5): the flow
// vector and
// C1, C2, C3 against finite differences of the regular potential, the flow vector on the ellipse
// against the thesis's g = f / pc (eq. 1.8), its bound near the hydrostatic axis, the overstress on
// and off the ellipse, zero volumetric flow at the critical state, the normal compression line
// under slow isotropic compression, and the sub-step stiffness.
#include "rktsph/materials/perzyna_modified_cam_clay.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "rktsph/materials/point_driver.hpp"
#include "stress_states.hpp"

namespace rktsph::perzyna_modified_cam_clay_test {
namespace {

using test_support::distance;
using test_support::finite_difference_gradient;
using test_support::principal_from_invariants;
using test_support::principal_invariants;
using test_support::random_rotation;
using test_support::rotated_principal;
using test_support::tensor_norm;

constexpr double kPi = std::numbers::pi;
constexpr double kFrictionAngle = 25.0;  // [deg]
constexpr double kPreconsolidation = 100e3;

PerzynaModifiedCamClay make_material(double fluidity, double exponent = 1.0) {
  ElasticConstants elastic;
  elastic.young_modulus = 10e6;
  elastic.poisson_ratio = 0.3;
  PerzynaModifiedCamClayParameters parameters;
  parameters.friction_angle = kFrictionAngle;
  parameters.compression_index = 0.2;
  parameters.swelling_index = 0.05;
  parameters.initial_void_ratio = 1.0;
  parameters.preconsolidation_pressure = kPreconsolidation;
  parameters.fluidity = fluidity;
  parameters.exponent = exponent;
  return PerzynaModifiedCamClay(1800.0, elastic, parameters);
}

/// M(theta) = 6 sin(phi) / (3 - sin(phi) sin 3theta), docs/theory.md §1.5.
double slope_m(double sin_3theta) {
  const double sin_phi = std::sin(kFrictionAngle * kPi / 180.0);
  return 6.0 * sin_phi / (3.0 - sin_phi * sin_3theta);
}

/// The thesis's g = (q^2 + M^2 p (p - pc)) / pc from eigenvalue invariants, independent of the
/// material.
double seed_potential(const SymmetricTensor& stress, double pc) {
  const auto invariants = principal_invariants(stress);
  const double m = slope_m(invariants.sin_3theta);
  const double p = invariants.pressure;
  return (invariants.q * invariants.q + m * m * p * (p - pc)) / pc;
}

/// (frozen_slope^2 / pc) g' with g' = q^2 / M(theta)^2 + p (p - pc). With frozen_slope = M at the
/// point of evaluation its gradient there is the flow vector the material uses (the M^2 / pc
/// scaling is a factor, not differentiated).
double regular_potential(const SymmetricTensor& stress, double pc, double frozen_slope) {
  const auto invariants = principal_invariants(stress);
  const double m = slope_m(invariants.sin_3theta);
  const double p = invariants.pressure;
  return frozen_slope * frozen_slope / pc * (invariants.q * invariants.q / (m * m) + p * (p - pc));
}

TEST(PerzynaModifiedCamClay, FlowVectorAndCoefficientsMatchGradientOfRegularPotential) {
  const PerzynaModifiedCamClay material = make_material(1.0);
  std::mt19937 generator(31);
  std::uniform_real_distribution<double> pressure(-0.2, 1.5), deviator(0.05, 1.5),
      lode(-25.0, 25.0), preconsolidation(0.5, 2.0);
  for (int sample = 0; sample < 20; ++sample) {
    const double pc = kPreconsolidation * preconsolidation(generator);
    const double theta = lode(generator) * kPi / 180.0;  // |sin 3theta| <= 0.91
    const SymmetricTensor stress = rotated_principal(
        principal_from_invariants(pressure(generator) * pc, deviator(generator) * pc, theta),
        random_rotation(generator));
    const double frozen_slope = slope_m(principal_invariants(stress).sin_3theta);
    const auto g = [pc, frozen_slope](const SymmetricTensor& s) {
      return regular_potential(s, pc, frozen_slope);
    };
    // Step 1 Pa on a 1e5 Pa scale: truncation ~ (1/1e4)^2 even for the theta terms, whose
    // length scale is sqrt(J2) >= 0.05 pc / sqrt3 ~ 3e3 Pa; round-off ~1e-15 * 1e5 / 1.
    const SymmetricTensor expected = finite_difference_gradient(g, stress, 1.0);
    const SymmetricTensor flow = material.flow_direction(stress, pc);
    EXPECT_LT(distance(flow, expected), 1e-6 * tensor_norm(expected)) << "sample " << sample;

    const FlowCoefficients c = material.flow_coefficients(stress_invariants(stress), pc);
    const std::array<double, 3> projected =
        test_support::project_on_invariant_gradients(expected, stress);
    // Compare each term C_i m_i at the scale |m|; |m1| = sqrt3, |m2| = 1/sqrt2, |m3| ~ J2. The
    // projection amplifies the finite-difference error by at most 1/(1 - 0.91^2) ~ 6.
    const double j2 = principal_invariants(stress).j2;
    const double scale = 1e-6 * tensor_norm(expected);
    EXPECT_NEAR(c.c1, projected[0], scale / std::sqrt(3.0));
    EXPECT_NEAR(c.c2, projected[1], scale * std::sqrt(2.0));
    EXPECT_NEAR(c.c3, projected[2], scale / j2);
  }
}

TEST(PerzynaModifiedCamClay, FlowVectorOnEllipseIsGradientOfSeedPotential) {
  // On f = 0 the regular flow vector must be the associated one of the thesis (eq. 1.8).
  const PerzynaModifiedCamClay material = make_material(1.0);
  std::mt19937 generator(5);
  std::uniform_real_distribution<double> pressure(0.1, 0.9), lode(-28.0, 28.0);
  for (int sample = 0; sample < 20; ++sample) {
    const double theta = lode(generator) * kPi / 180.0;
    const double p = pressure(generator) * kPreconsolidation;
    const double q = slope_m(std::sin(3.0 * theta)) * std::sqrt(p * (kPreconsolidation - p));
    const SymmetricTensor stress =
        rotated_principal(principal_from_invariants(p, q, theta), random_rotation(generator));
    const auto g = [](const SymmetricTensor& s) { return seed_potential(s, kPreconsolidation); };
    // q >= M sqrt(0.09) pc ~ 3e4 Pa: the 1 Pa step keeps the truncation near 1e-9 relative.
    const SymmetricTensor expected = finite_difference_gradient(g, stress, 1.0);
    EXPECT_LT(distance(material.flow_direction(stress, kPreconsolidation), expected),
              1e-6 * tensor_norm(expected))
        << "sample " << sample;
  }
}

TEST(PerzynaModifiedCamClay, FlowVectorStaysBoundedNearHydrostaticAxis) {
  // Off the critical state (p != pc/2) and off the ellipse, as q -> 0 at fixed theta, m must
  // tend to its hydrostatic value M^2 (2p - pc)/pc dp/dstress = -M^2 (2p - pc)/(3 pc) I. The rest
  // is 2q dq/pc (size sqrt(3/2) 2q/pc, as |dq| = sqrt(3/2)) plus the theta term
  // 2q^2/(M pc) |dM/dtheta| |dtheta| with |dtheta| = sqrt(3/2)/q and |dM/dtheta| <= 18 sin^2(phi)
  // /(3 - sin phi)^2 = 0.50 for phi = 25°, M >= 0.82: at most 1.5 q/pc. Bound: 5 q/pc.
  // (The thesis's theta term, 2M p (p - pc)/pc dM, would instead grow like pc/q.)
  const PerzynaModifiedCamClay material = make_material(1.0);
  std::mt19937 generator(23);
  for (double pressure_ratio : {0.1, 0.3, 0.8, 1.2}) {
    for (double theta_degrees : {-20.0, 10.0, 25.0}) {
      const double theta = theta_degrees * kPi / 180.0;
      const double p = pressure_ratio * kPreconsolidation;
      const double slope = slope_m(std::sin(3.0 * theta));
      const double axial =
          -slope * slope * (2.0 * p - kPreconsolidation) / (3.0 * kPreconsolidation);
      const SymmetricTensor axis_value = {axial, axial, axial, 0.0, 0.0, 0.0};
      const Eigen::Matrix3d rotation = random_rotation(generator);
      for (double q_ratio : {1e-2, 1e-4, 1e-6}) {
        const double q = q_ratio * kPreconsolidation;
        const SymmetricTensor flow = material.flow_direction(
            rotated_principal(principal_from_invariants(p, q, theta), rotation), kPreconsolidation);
        EXPECT_LT(distance(flow, axis_value), 5.0 * q_ratio + 1e-9)
            << "p/pc " << pressure_ratio << " theta " << theta_degrees << " q/pc " << q_ratio;
      }
    }
  }
}

TEST(PerzynaModifiedCamClay, FlowVectorHasNoSingularityAtLodeLimits) {
  // C2 and C3 carry cos 3theta only through dM/dtheta, so m is continuous up to theta = +-30°.
  const PerzynaModifiedCamClay material = make_material(1.0);
  for (double sign : {1.0, -1.0}) {
    const auto at = [&](double theta) {
      return material.flow_direction(rotated_principal(principal_from_invariants(60e3, 70e3, theta),
                                                       Eigen::Matrix3d::Identity()),
                                     kPreconsolidation);
    };
    const SymmetricTensor limit = at(sign * kPi / 6.0);
    const SymmetricTensor near = at(sign * (kPi / 6.0 - 1e-6));
    for (double component : limit)
      EXPECT_TRUE(std::isfinite(component));
    // m is Lipschitz in theta with a constant of order |m|: a 1e-6 rad move changes it ~1e-6.
    EXPECT_LT(distance(limit, near), 1e-5 * tensor_norm(limit));
  }
}

TEST(PerzynaModifiedCamClay, OverstressVanishesOnEllipseAndGrowsOutside) {
  const PerzynaModifiedCamClay linear = make_material(1.0, 1.0);
  const PerzynaModifiedCamClay squared = make_material(1.0, 2.0);
  const std::array<double, 2> internal = {0.0, kPreconsolidation};
  std::mt19937 generator(7);
  for (double pressure_ratio : {0.05, 0.3, 0.5, 0.8, 0.99}) {
    for (double theta_degrees : {-30.0, -12.0, 0.0, 17.0, 30.0}) {
      const double theta = theta_degrees * kPi / 180.0;
      const double p = pressure_ratio * kPreconsolidation;
      const double m = slope_m(std::sin(3.0 * theta));
      const double q_on = m * std::sqrt(p * (kPreconsolidation - p));
      const Eigen::Matrix3d rotation = random_rotation(generator);
      const auto at = [&](double q) {
        return rotated_principal(principal_from_invariants(p, q, theta), rotation);
      };
      // On the ellipse f = 0 up to round-off of terms of size (M p)^2 ~ pc^2 after a rotation:
      // ~1e-15 pc^2, so Psi (N = 1) below 1e-12.
      EXPECT_LT(linear.overstress(at(q_on), internal), 1e-12);
      EXPECT_EQ(linear.overstress(at(0.9 * q_on), internal), 0.0);
      // Outside, Psi = ((q^2 - q_on^2)/pc^2)^N: Macaulay first, then the power.
      const double q_out = 1.01 * q_on;
      const double expected =
          (q_out * q_out - q_on * q_on) / (kPreconsolidation * kPreconsolidation);
      EXPECT_NEAR(linear.overstress(at(q_out), internal), expected, 1e-9 * expected);
      EXPECT_NEAR(squared.overstress(at(q_out), internal), expected * expected,
                  2e-9 * expected * expected);
    }
  }
  // Beyond the tip (p > pc) and on the tension side (p < 0) even an isotropic state flows.
  EXPECT_GT(linear.overstress({-1.1e5, -1.1e5, -1.1e5, 0, 0, 0}, internal), 0.0);
  EXPECT_GT(linear.overstress({1e3, 1e3, 1e3, 0, 0, 0}, internal), 0.0);
  EXPECT_EQ(linear.overstress({-0.9e5, -0.9e5, -0.9e5, 0, 0, 0}, internal), 0.0);
}

TEST(PerzynaModifiedCamClay, NoVolumetricFlowAtCriticalState) {
  // At p = pc/2, dg/dp = M^2 (2p - pc)/pc = 0, so the flow is purely deviatoric and pc is steady.
  const PerzynaModifiedCamClay material = make_material(2.0);
  const std::array<double, 2> internal = {0.0, kPreconsolidation};
  std::mt19937 generator(13);
  for (double theta_degrees : {-30.0, -20.0, 0.0, 10.0, 30.0}) {
    const double theta = theta_degrees * kPi / 180.0;
    const double p = 0.5 * kPreconsolidation;
    const double q = 1.05 * slope_m(std::sin(3.0 * theta)) * p;  // just outside the ellipse
    const SymmetricTensor stress =
        rotated_principal(principal_from_invariants(p, q, theta), random_rotation(generator));
    SymmetricTensor strain_rate;
    std::array<double, 2> internal_rate{};
    material.viscoplastic_rate(stress, internal, strain_rate, internal_rate);
    const double size = tensor_norm(strain_rate);
    ASSERT_GT(size, 0.0);
    // Round-off of the rotation: ~1e-15 of the stress scale, far below 1e-10 of |rate|.
    EXPECT_NEAR(strain_rate[0] + strain_rate[1] + strain_rate[2], 0.0, 1e-10 * size);
    EXPECT_NEAR(internal_rate[PerzynaModifiedCamClay::kPreconsolidationPressure], 0.0,
                1e-10 * size * kPreconsolidation * 20.0);
    // The equivalent strain rate of docs/theory.md §1.3, computed here: with zero trace it is
    // sqrt(2/3) |rate|.
    EXPECT_NEAR(internal_rate[PerzynaModifiedCamClay::kEquivalentStrain],
                std::sqrt(2.0 / 3.0) * size, 1e-9 * size);
  }
}

TEST(PerzynaModifiedCamClay, WetSideCompactsAndHardensDrySideDilatesAndSoftens) {
  const PerzynaModifiedCamClay material = make_material(2.0);
  const std::array<double, 2> internal = {0.0, kPreconsolidation};
  for (double pressure_ratio : {0.3, 0.8}) {
    const double p = pressure_ratio * kPreconsolidation;
    const double q = 1.1 * slope_m(1.0) * std::sqrt(p * (kPreconsolidation - p));
    SymmetricTensor strain_rate;
    std::array<double, 2> internal_rate{};
    material.viscoplastic_rate(
        rotated_principal(principal_from_invariants(p, q, kPi / 6.0), Eigen::Matrix3d::Identity()),
        internal, strain_rate, internal_rate);
    const double volumetric = strain_rate[0] + strain_rate[1] + strain_rate[2];
    // Hardening law, docs/theory.md §1.5: pc_rate = -((1 + e0)/(lambda - kappa)) pc
    // tr(eps_vp_rate).
    const double factor = (1.0 + 1.0) / (0.2 - 0.05);
    EXPECT_NEAR(internal_rate[1], -factor * kPreconsolidation * volumetric,
                1e-12 * factor * kPreconsolidation * std::abs(volumetric));
    if (pressure_ratio > 0.5) {
      EXPECT_LT(volumetric, 0.0);  // compaction (tension positive)
      EXPECT_GT(internal_rate[1], 0.0);
    } else {
      EXPECT_GT(volumetric, 0.0);  // dilation
      EXPECT_LT(internal_rate[1], 0.0);
    }
  }
}

/// Rate-independent isotropic compression from p = pc0 on the NCL: the volumetric strain
/// (compression positive) is elastic (p - pc0)/K plus plastic ln(p/pc0) (lambda - kappa)/(1+e0).
/// Solved for p by bisection (the left side grows monotonically with p).
double normal_compression_pressure(double volumetric_strain, double bulk_modulus,
                                   double plastic_slope) {
  double low = kPreconsolidation,
         high = kPreconsolidation * std::exp(volumetric_strain / plastic_slope);
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double middle = 0.5 * (low + high);
    const double strain = (middle - kPreconsolidation) / bulk_modulus +
                          plastic_slope * std::log(middle / kPreconsolidation);
    (strain < volumetric_strain ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

TEST(PerzynaModifiedCamClay, SlowIsotropicCompressionFollowsNormalCompressionLine) {
  const double compression_rate = 1e-2, fluidity = 1e3;
  const PerzynaModifiedCamClay material = make_material(fluidity);
  const double bulk_modulus = material.elastic().bulk_modulus();
  const double plastic_slope = (0.2 - 0.05) / (1.0 + 1.0);
  // Overstress bound: at p >= pc the plastic volumetric rate is at least gamma M^4 delta with
  // delta = (p - pc)/pc and M = M(theta = 0) (the Lode angle is undefined on the axis), and it
  // cannot exceed the imposed rate, so delta <= rate / (gamma M^4) ~ 2e-5. It shifts p above the
  // rate-independent value and the NCL by at most delta (relative) and delta * slope.
  const double overstress_bound = compression_rate / (fluidity * std::pow(slope_m(0.0), 4));
  const double rate = -compression_rate / 3.0;
  DriveOptions options;
  options.time_step = 0.01;
  options.record_every = 50;
  const PointState start = initial_point_state(
      material, {-kPreconsolidation, -kPreconsolidation, -kPreconsolidation, 0, 0, 0});
  const auto history =
      drive(material, StrainPath::constant_strain_rate({rate, rate, rate, 0, 0, 0}, 10.0), start,
            options);
  ASSERT_EQ(history.size(), 21u);
  for (const PointState& state : history) {
    const double volumetric_strain = -(state.strain[0] + state.strain[1] + state.strain[2]);
    const double p = -(state.stress[0] + state.stress[1] + state.stress[2]) / 3.0;
    const double pc = state.internal[PerzynaModifiedCamClay::kPreconsolidationPressure];
    const double reference =
        normal_compression_pressure(volumetric_strain, bulk_modulus, plastic_slope);
    EXPECT_NEAR(p / reference, 1.0, overstress_bound) << "t = " << state.time;
    EXPECT_LE(pc, p * (1.0 + 1e-12));
    EXPECT_GE(pc, p * (1.0 - overstress_bound));
    // The plastic volumetric strain from the state (total minus elastic (p - pc0)/K) against
    // the NCL at the current p.
    const double plastic_strain = volumetric_strain - (p - kPreconsolidation) / bulk_modulus;
    EXPECT_NEAR(plastic_strain, plastic_slope * std::log(p / kPreconsolidation),
                plastic_slope * overstress_bound + 1e-12);
  }
  // The path did go far up the NCL: pc grew by a factor ~2.
  EXPECT_GT(history.back().internal[1], 1.8 * kPreconsolidation);
}

TEST(PerzynaModifiedCamClay, SourceStiffnessMatchesLinearisedRelaxationRate) {
  // Leading term of the source Jacobian (N = 1): -gamma d (x) dPsi/dy with d = (D:m, A pc tr m),
  // dPsi/dstress = m/pc and dPsi/dpc = -M^2 p/pc^2 - 2 Psi/pc. Along d its size is
  // gamma |dPsi.d|; along the stress part of d alone it is gamma (m:D:m/pc) |d|/|D:m|. The
  // estimate is the larger. Neglected: gamma Psi |dd/dy|, relative size ~Psi = 1e-5 here, and the
  // one-sided step 1e-6 pc, so 1e-3 relative is a safe tolerance.
  const double fluidity = 5.0;
  const PerzynaModifiedCamClay material = make_material(fluidity);
  const ElasticConstants& elastic = material.elastic();
  const double factor = (1.0 + 1.0) / (0.2 - 0.05);
  std::mt19937 generator(41);
  for (double pressure_ratio : {0.2, 0.5, 0.9, 1.0}) {
    for (double theta_degrees : {-30.0, 5.0, 30.0}) {
      const double theta = theta_degrees * kPi / 180.0;
      const double p = pressure_ratio * kPreconsolidation;
      const double m_slope = slope_m(std::sin(3.0 * theta));
      const double psi = 1e-5;
      // q^2 = psi pc^2 - M^2 p (p - pc): a state with Psi = 1e-5.
      const double q = std::sqrt(psi * kPreconsolidation * kPreconsolidation -
                                 m_slope * m_slope * p * (p - kPreconsolidation));
      const SymmetricTensor stress =
          rotated_principal(principal_from_invariants(p, q, theta), random_rotation(generator));
      const std::array<double, 2> internal = {0.0, kPreconsolidation};
      const SymmetricTensor m = material.flow_direction(stress, kPreconsolidation);
      const double trace_m = m[0] + m[1] + m[2];
      SymmetricTensor stiffness_m;
      const double lambda = elastic.lame_lambda(), shear = elastic.shear_modulus();
      for (int i = 0; i < 6; ++i)
        stiffness_m[i] = 2.0 * shear * m[i] + (i < 3 ? lambda * trace_m : 0.0);
      double m_d_m = 0.0;
      for (int i = 0; i < 6; ++i)
        m_d_m += (i < 3 ? 1.0 : 2.0) * m[i] * stiffness_m[i];
      const double hardening_part = factor * kPreconsolidation * trace_m;
      const double d_psi_d_pc = -m_slope * m_slope * p / (kPreconsolidation * kPreconsolidation) -
                                2.0 * psi / kPreconsolidation;
      const double along_d =
          fluidity * std::abs(m_d_m / kPreconsolidation + d_psi_d_pc * hardening_part);
      const double d_norm = std::sqrt(tensor_norm(stiffness_m) * tensor_norm(stiffness_m) +
                                      hardening_part * hardening_part);
      const double along_stress =
          fluidity * m_d_m / kPreconsolidation * d_norm / tensor_norm(stiffness_m);
      const double expected = std::max(along_d, along_stress);
      EXPECT_NEAR(material.source_stiffness(stress, internal) / expected, 1.0, 1e-3)
          << "p/pc " << pressure_ratio << " theta " << theta_degrees;
    }
  }
  // Deep inside the ellipse the source is zero and so is its stiffness.
  EXPECT_EQ(material.source_stiffness({-5e4, -5e4, -5e4, 0, 0, 0}, std::array<double, 2>{0.0, 1e5}),
            0.0);
}

}  // namespace
}  // namespace rktsph::perzyna_modified_cam_clay_test
