// Perzyna Mohr–Coulomb on a single material point (docs/theory.md §1.8): the hexagon against the
// textbook function, triaxial compression and extension at the exact corners, plane-strain simple
// shear against Davis's closed form, the dilatancy of each, the Koiter flow at a corner (its closed
// form, and that it does not depend on the eigenvectors picked), the relaxation on a face at the
// Perzyna rate, and a path through the apex.
#include "rktsph/materials/perzyna_mohr_coulomb.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "flow_memory.hpp"
#include "frictional_closed_forms.hpp"
#include "rktsph/materials/point_driver.hpp"
#include "stress_states.hpp"

namespace rktsph::perzyna_mohr_coulomb_test {
namespace {

using test_support::distance;
using test_support::principal_invariants;
using test_support::random_rotation;
using test_support::rotated_principal;
using test_support::tensor_norm;
using test_support::to_radians;

constexpr double kCohesion = 10e3;       // [Pa]
constexpr double kFrictionAngle = 30.0;  // [deg]
constexpr double kDilatancyAngle = 10.0;
constexpr double kConfining = 100e3;  // [Pa], compression
constexpr double kReference = 10e3;   // F0 [Pa]

ElasticConstants soil_elasticity() {
  ElasticConstants elastic;
  elastic.young_modulus = 20e6;
  elastic.poisson_ratio = 0.3;
  return elastic;
}

PerzynaMohrCoulomb make_material(double fluidity, double exponent = 1.0) {
  FrictionalParameters p;
  p.cohesion = kCohesion;
  p.friction_angle = kFrictionAngle;
  p.dilatancy_angle = kDilatancyAngle;
  p.fluidity = fluidity;
  p.exponent = exponent;
  p.reference_stress = kReference;
  return PerzynaMohrCoulomb(2000.0, soil_elasticity(), p);
}

/// Eigenvalues, largest (least compressive) first.
std::array<double, 3> sorted_principal(const SymmetricTensor& stress) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(test_support::to_matrix(stress),
                                                              Eigen::EigenvaluesOnly);
  return {solver.eigenvalues()[2], solver.eigenvalues()[1], solver.eigenvalues()[0]};
}

/// The textbook Mohr–Coulomb function (sigma1 - sigma3)/2 + (sigma1 + sigma3)/2 sin phi - c cos
/// phi, tension positive, sigma1 the largest principal stress.
double textbook_function(const SymmetricTensor& stress) {
  const auto s = sorted_principal(stress);
  const double phi = to_radians(kFrictionAngle);
  return 0.5 * (s[0] - s[2]) + 0.5 * (s[0] + s[2]) * std::sin(phi) - kCohesion * std::cos(phi);
}

double volumetric(const SymmetricTensor& strain) {
  return strain[0] + strain[1] + strain[2];
}

DriveOptions options_with_step(double time_step, int record_every = 1) {
  DriveOptions options;
  options.time_step = time_step;
  options.record_every = record_every;
  return options;
}

const SymmetricTensor kIsotropic = {-kConfining, -kConfining, -kConfining, 0.0, 0.0, 0.0};

std::vector<double> initial_internal(const PerzynaMohrCoulomb& material) {
  std::vector<double> internal(3);
  material.initial_internal(internal);
  return internal;
}

TEST(PerzynaMohrCoulomb, YieldFunctionIsTheHexagon) {
  const auto material = make_material(1.0);
  const auto internal = initial_internal(material);
  std::mt19937 generator(31);
  std::uniform_real_distribution<double> principal(-400e3, 30e3);
  for (int k = 0; k < 20; ++k) {
    const SymmetricTensor stress =
        rotated_principal({principal(generator), principal(generator), principal(generator)},
                          random_rotation(generator));
    // Round-off of eigenvalues of stresses of 4e5 Pa: ~1e-10 relative.
    EXPECT_NEAR(material.yield_function(stress, internal), textbook_function(stress), 1e-4);
  }
}

TEST(PerzynaMohrCoulomb, TriaxialCompressionReachesTheExactCorner) {
  // The hexagon is not rounded, so the compression corner is Mohr–Coulomb's own: sigma_a =
  // sigma_c Kp + 2c sqrt Kp = 334.6 kPa. Both corner planes flow with overstress F = F0 eps_rate /
  // (gamma (1 - sin psi)) = 1.2 Pa (axial flow (sin psi - 1) per plane pair), which moves sigma_a
  // by F / 0.25 = 4.8 Pa (dF/dsigma_3 = (sin phi - 1)/2): 1.4e-5. Tolerance 5e-5.
  const auto material = make_material(10.0);
  const auto history =
      drive(material, StrainPath::uniaxial_stress(-1e-3, 30.0),
            initial_point_state(material, kIsotropic), options_with_step(0.01, 10));
  const PointState& last = history.back();
  const double expected = test_support::major_at_failure(kConfining, kCohesion, kFrictionAngle);
  EXPECT_NEAR(-last.stress[0], expected, 5e-5 * expected);
  // Dilatancy at steady flow (the stress is constant, the strain increments are viscoplastic):
  // -2 sin psi / (1 - sin psi); round-off of the stress drift only, 1e-6.
  const PointState& earlier = history[history.size() - 11];
  const double ratio =
      (volumetric(last.strain) - volumetric(earlier.strain)) / (last.strain[0] - earlier.strain[0]);
  EXPECT_NEAR(ratio, test_support::triaxial_compression_dilatancy(kDilatancyAngle), 1e-6);
}

TEST(PerzynaMohrCoulomb, TriaxialExtensionReachesTheExactCorner) {
  // sigma_a = (sigma_c - 2c sqrt Kp)/Kp = 21.8 kPa; overstress F0 eps_rate/(gamma (1 + sin psi))
  // = 0.85 Pa moves sigma_a by F/0.75 = 1.1 Pa: 5e-5 of sigma_a. Tolerance 2e-4.
  const auto material = make_material(10.0);
  const auto history =
      drive(material, StrainPath::uniaxial_stress(1e-3, 15.0),
            initial_point_state(material, kIsotropic), options_with_step(0.01, 10));
  const PointState& last = history.back();
  const double expected = test_support::minor_at_failure(kConfining, kCohesion, kFrictionAngle);
  EXPECT_NEAR(-last.stress[0], expected, 2e-4 * expected);
  const PointState& earlier = history[history.size() - 11];
  const double ratio =
      (volumetric(last.strain) - volumetric(earlier.strain)) / (last.strain[0] - earlier.strain[0]);
  EXPECT_NEAR(ratio, test_support::triaxial_extension_dilatancy(kDilatancyAngle), 1e-6);
}

TEST(PerzynaMohrCoulombSlow, PlaneStrainSimpleShearMatchesDavis) {
  // Davis's steady shear stress (63.3 kPa) and dilation eps_yy_rate/gamma_xy_rate = tan psi. The
  // face's overstress F = F0 (eps1 - eps3)_rate / gamma = 1e4 * 1e-3 / 10 = 1 Pa raises t by ~1
  // Pa: 1.6e-5 of tau; tolerance 5e-5. The transient decays on the elastic strain scale (0.008):
  // after 0.1 of shear the dilatancy ratio was still 4e-5 off, after 0.2 it is at 1e-8; 1e-5.
  const auto material = make_material(10.0);
  const auto history =
      drive(material, test_support::simple_shear(1e-3, 200.0),
            initial_point_state(material, kIsotropic), options_with_step(0.02, 10));
  const PointState& last = history.back();
  const double expected =
      test_support::simple_shear_strength(kConfining, kCohesion, kFrictionAngle, kDilatancyAngle);
  EXPECT_NEAR(std::abs(last.stress[3]), expected, 5e-5 * expected);
  EXPECT_NEAR(last.stress[1], -kConfining, 1e-6 * kConfining);
  // sigma_zz is the intermediate stress (only the in-plane face flows, eps_zz^vp = 0).
  const auto principal = sorted_principal(last.stress);
  EXPECT_LT(last.stress[2], principal[0]);
  EXPECT_GT(last.stress[2], principal[2]);
  const PointState& earlier = history[history.size() - 11];
  const double dilation = last.strain[1] - earlier.strain[1];
  const double shear = 2.0 * (last.strain[3] - earlier.strain[3]);
  EXPECT_NEAR(dilation / shear, std::tan(to_radians(kDilatancyAngle)), 1e-5);
}

TEST(PerzynaMohrCoulomb, KoiterFlowAtTheCompressionCorner) {
  // At sigma1 = sigma2 > sigma3 the planes (1,3) and (2,3) have the same overstress F, and the
  // flow is gamma F/F0 (dg13 + dg23): principal components ((1 + sin psi)/2, (1 + sin psi)/2,
  // sin psi - 1). Rotating the stress rotates the flow, although the solver's eigenvectors of the
  // repeated pair are arbitrary.
  const double fluidity = 2.0;
  const auto material = make_material(fluidity);
  const auto internal = initial_internal(material);
  const std::array<double, 3> corner = {-100e3, -100e3, -400e3};
  const double overstress =
      textbook_function(rotated_principal(corner, Eigen::Matrix3d::Identity()));
  ASSERT_GT(overstress, 0.0);
  const double rate = fluidity * overstress / kReference;
  const double sin_psi = std::sin(to_radians(kDilatancyAngle));
  const std::array<double, 3> expected_principal = {
      rate * (1.0 + sin_psi) / 2.0, rate * (1.0 + sin_psi) / 2.0, rate * (sin_psi - 1.0)};
  std::mt19937 generator(5);
  std::vector<double> internal_rate(3);
  for (int k = 0; k < 5; ++k) {
    const Eigen::Matrix3d rotation = random_rotation(generator);
    SymmetricTensor strain_rate;
    material.viscoplastic_rate(rotated_principal(corner, rotation), internal, strain_rate,
                               internal_rate);
    const SymmetricTensor expected = rotated_principal(expected_principal, rotation);
    // Round-off of eigenvectors and of the rotation: 1e-12 relative.
    EXPECT_LT(distance(strain_rate, expected), 1e-10 * tensor_norm(expected));
  }
  // Continuity across the corner: 1 Pa off it the flow moves by O(gamma/F0 * 1 Pa), not O(rate).
  SymmetricTensor at_corner, off_corner;
  material.viscoplastic_rate(rotated_principal(corner, Eigen::Matrix3d::Identity()), internal,
                             at_corner, internal_rate);
  material.viscoplastic_rate(
      rotated_principal({-100e3 + 1.0, -100e3, -400e3}, Eigen::Matrix3d::Identity()), internal,
      off_corner, internal_rate);
  EXPECT_LT(distance(at_corner, off_corner), 2.0 * fluidity / kReference);
}

TEST(PerzynaMohrCoulomb, RelaxesToTheFaceAtThePerzynaRate) {
  // Total strain held, one face (1,3) flowing and the others well inside: F_13 decays as
  // dF/dt = -a gamma (F/F0)^N, a = dF/dsigma : D : dg/dsigma = G (1 + sin phi sin psi) + lambda
  // sin phi sin psi, constant on the face (coaxial flow, fixed principal axes).
  const ElasticConstants elastic = soil_elasticity();
  const double sin_phi = std::sin(to_radians(kFrictionAngle));
  const double sin_psi = std::sin(to_radians(kDilatancyAngle));
  const double a = elastic.shear_modulus() * (1.0 + sin_phi * sin_psi) +
                   elastic.lame_lambda() * sin_phi * sin_psi;
  std::mt19937 generator(8);
  const SymmetricTensor start =
      rotated_principal({-50e3, -100e3, -250e3}, random_rotation(generator));
  const double initial = textbook_function(start);  // 16.3 kPa
  for (const double exponent : {1.0, 2.0}) {
    const double fluidity = 1.0;
    const auto material = make_material(fluidity, exponent);
    const double rate = a * fluidity / kReference;  // ~940 1/s
    // RK4 error ~ (rate dt)^5/120 per step = 2e-11 at rate dt = 0.019; 1e-8 over the run.
    const auto history = drive(material, StrainPath::constant_strain_rate({}, 5.0 / rate),
                               initial_point_state(material, start), options_with_step(2e-5));
    for (std::size_t index = 50; index < history.size(); index += 50) {
      const double t = history[index].time;
      const double expected = exponent == 1.0 ? initial * std::exp(-rate * t)
                                              : initial / (1.0 + rate * initial / kReference * t);
      EXPECT_NEAR(textbook_function(history[index].stress) / expected, 1.0, 1e-6)
          << "N = " << exponent << ", t = " << t;
    }
    if (exponent == 1.0) {  // the sub-step stiffness is exact on a face
      EXPECT_NEAR(material.source_stiffness(start, history.front().internal), rate, 1e-9 * rate);
    }
  }
}

TEST(PerzynaMohrCoulomb, PathThroughTheApexSettlesAtTheApex) {
  // From a compressive state with a deviator, stretched isotropically past the apex c cot phi:
  // all six planes and the three tension planes (at the apex by default) flow. With N = 1 their
  // deviatoric flows add to (5/2) gamma s / F0, so the deviator vanishes, and each principal
  // strain rate is taken by gamma (sigma - apex)(1 + 2 sin phi sin psi) / F0: the steady stress
  // is the apex plus F0 eps_rate / (gamma (1 + 2 sin phi sin psi)) (8.5 Pa here).
  const double fluidity = 1.0, strain_rate = 1e-3;
  const auto material = make_material(fluidity);
  const SymmetricTensor start = {-80e3, -40e3, -30e3, 10e3, 0.0, 5e3};
  const auto history =
      drive(material,
            StrainPath::constant_strain_rate({strain_rate, strain_rate, strain_rate, 0, 0, 0}, 5.0),
            initial_point_state(material, start), options_with_step(1e-3, 100));
  const double sin_phi = std::sin(to_radians(kFrictionAngle));
  const double sin_psi = std::sin(to_radians(kDilatancyAngle));
  const double apex = kCohesion / std::tan(to_radians(kFrictionAngle));
  const double expected =
      apex + kReference * strain_rate / (fluidity * (1.0 + 2.0 * sin_phi * sin_psi));
  const PointState& last = history.back();
  // A fixed point of the ODE reached at rates >= 2G (5/2) gamma / F0 ~ 4e3 /s over seconds:
  // round-off only (1e-6 of F0).
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(last.stress[i], expected, 1e-6 * kReference) << "component " << i;
  for (int i = 3; i < 6; ++i)
    EXPECT_NEAR(last.stress[i], 0.0, 1e-6 * kReference) << "component " << i;
}

/// Largest |eigenvalue| of the Jacobian of the stress source S(sigma) = -D : eps_vp_rate(sigma),
/// by central differences (D built here: lambda tr(e) I + 2G e).
double measured_relaxation_rate(const Material& material, const SymmetricTensor& stress,
                                const std::vector<double>& internal) {
  const ElasticConstants elastic = material.elastic();
  const auto source = [&](const SymmetricTensor& at) {
    SymmetricTensor rate;
    std::vector<double> internal_rate(internal.size());
    material.viscoplastic_rate(at, internal, rate, internal_rate);
    const double volumetric = elastic.lame_lambda() * (rate[0] + rate[1] + rate[2]);
    SymmetricTensor result;
    for (int i = 0; i < 6; ++i)
      result[i] = -2.0 * elastic.shear_modulus() * rate[i] - (i < 3 ? volumetric : 0.0);
    return result;
  };
  Eigen::Matrix<double, 6, 6> jacobian;
  const double step = 1.0;  // [Pa] on stresses of 1e5: truncation ~1e-10 of a smooth source
  for (int column = 0; column < 6; ++column) {
    SymmetricTensor plus = stress, minus = stress;
    plus[column] += step;
    minus[column] -= step;
    const SymmetricTensor up = source(plus), down = source(minus);
    for (int row = 0; row < 6; ++row)
      jacobian(row, column) = (up[row] - down[row]) / (2.0 * step);
  }
  return jacobian.eigenvalues().cwiseAbs().maxCoeff();
}

TEST(PerzynaMohrCoulomb, SubStepStiffnessBoundsTheRelaxationRate) {
  // The sub-step rule (docs/theory.md eq. 2.7) needs the source's fastest rate. Near a corner two
  // planes flow, and beyond the apex all nine: the Gershgorin bound (eq. 1.18) must not be below
  // the largest eigenvalue of the Jacobian, and should not be far above it (sub-steps wasted).
  const auto material = make_material(2.0);
  const auto internal = initial_internal(material);
  std::mt19937 generator(12);
  const double apex = kCohesion / std::tan(to_radians(kFrictionAngle));
  for (const std::array<double, 3> principal :
       {std::array<double, 3>{-95e3, -100e3, -400e3}, std::array<double, 3>{-60e3, -100e3, -300e3},
        std::array<double, 3>{apex + 3e3, apex + 2e3, apex + 1e3}}) {
    const SymmetricTensor stress = rotated_principal(principal, random_rotation(generator));
    const double measured = measured_relaxation_rate(material, stress, internal);
    const double bound = material.source_stiffness(stress, internal);
    // Finite-difference error ~1e-6 relative; the bound may exceed the rate by the off-diagonal
    // couplings it adds up (a factor below 3 here).
    EXPECT_GE(bound, measured * (1.0 - 1e-6)) << principal[0];
    EXPECT_LE(bound, 3.0 * measured) << principal[0];
  }
}

TEST(PerzynaMohrCoulomb, NoFlowInsideTheHexagon) {
  const auto material = make_material(5.0);
  const auto internal = initial_internal(material);
  SymmetricTensor strain_rate;
  std::vector<double> internal_rate(3, 1.0);
  const SymmetricTensor inside = {-100e3, -150e3, -200e3, 10e3, 0.0, 0.0};
  ASSERT_LT(textbook_function(inside), 0.0);
  material.viscoplastic_rate(inside, internal, strain_rate, internal_rate);
  EXPECT_EQ(tensor_norm(strain_rate), 0.0);
  EXPECT_EQ(internal_rate, (std::vector<double>{0.0, 0.0, 0.0}));
  EXPECT_FALSE(material.flows(inside, internal));
}

// Issue 30: a point that has flowed says so after it has unloaded (eps_vp > 0), so that the
// zero-energy controls that follow flow (docs/theory.md eqs. 3.10, 3.14) keep its cell at the
// near-flow strength. Without it a cell at yield switched between no control and the full one
// from step to step, which held a slope near failure in a never-ending oscillation (§10.4).
TEST(PerzynaMohrCoulomb, RemembersThatItHasFlowed) {
  test_support::expect_remembers_its_flow(make_material(10.0), kIsotropic);
}

}  // namespace
}  // namespace rktsph::perzyna_mohr_coulomb_test
