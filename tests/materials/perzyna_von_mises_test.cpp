// Perzyna Von Mises on a single material point (docs/theory.md §1.3, §1.4, §2.8): closed-form
// relaxation, the slow-rate limit of hardening and softening, the flow vector against finite
// differences of q, and the sub-step stiffness.
#include "rktsph/materials/perzyna_von_mises.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "rktsph/materials/point_driver.hpp"
#include "stress_states.hpp"

namespace rktsph::perzyna_von_mises_test {
namespace {

using test_support::distance;
using test_support::finite_difference_gradient;
using test_support::principal_invariants;
using test_support::random_rotation;
using test_support::rotated_principal;
using test_support::tensor_norm;

ElasticConstants soil_elasticity() {
  ElasticConstants elastic;
  elastic.young_modulus = 10e6;
  elastic.poisson_ratio = 0.3;
  return elastic;
}

PerzynaVonMises make_material(double hardening_modulus, double fluidity, double exponent = 1.0,
                              double minimum_yield_stress = 1e3) {
  PerzynaVonMisesParameters parameters;
  parameters.yield_stress = 100e3;
  parameters.hardening_modulus = hardening_modulus;
  parameters.fluidity = fluidity;
  parameters.exponent = exponent;
  parameters.minimum_yield_stress = minimum_yield_stress;
  return PerzynaVonMises(2000.0, soil_elasticity(), parameters);
}

TEST(PerzynaVonMises, UniaxialRelaxationIsExponential) {
  // Total strain held after an elastic overshoot, lateral stresses held at 0: in uniaxial stress
  // m_xx = 1, so sigma_rate = -E gamma (sigma - Y)/Y and sigma - Y = (sigma0 - Y) exp(-E gamma
  // t/Y).
  const double fluidity = 0.1;
  const PerzynaVonMises material = make_material(0.0, fluidity);
  const double young = material.elastic().young_modulus;
  const double yield = material.parameters().yield_stress;
  const double rate = young * fluidity / yield;  // 10 1/s
  const double initial = 1.5 * yield;

  DriveOptions options;
  // RK4 on y' = -rate y loses (rate dt)^5/120 per step relative: 160 steps of rate dt = 0.025
  // give 1.3e-8, well inside the 1e-6 asked for.
  options.time_step = 0.0025;
  const auto history =
      drive(material, StrainPath::uniaxial_stress(0.0, 0.4),
            initial_point_state(material, {initial, 0.0, 0.0, 0.0, 0.0, 0.0}), options);
  ASSERT_EQ(history.size(), 161u);
  for (std::size_t index : {20u, 40u, 80u, 160u}) {
    const PointState& state = history[index];
    const double expected = (initial - yield) * std::exp(-rate * state.time);
    EXPECT_NEAR((state.stress[0] - yield) / expected, 1.0, 1e-6) << "t = " << state.time;
    // Lateral stresses stay at zero (stress-controlled) and the axial total strain at 0.
    EXPECT_NEAR(state.stress[1], 0.0, 1e-6);
    EXPECT_NEAR(state.stress[2], 0.0, 1e-6);
    EXPECT_NEAR(state.strain[0], 0.0, 1e-15);
    // The axial viscoplastic strain is what the stress lost, over E; in uniaxial flow it equals
    // the equivalent strain of docs/theory.md §1.3.
    EXPECT_NEAR(state.internal[PerzynaVonMises::kEquivalentStrain],
                (initial - state.stress[0]) / young, 1e-6 * (initial - yield) / young);
    EXPECT_EQ(state.internal[PerzynaVonMises::kYieldStress], yield);
  }
}

/// Uniaxial stress at constant strain rate. Rate-independent reference: with
/// eps_vp_eq = eps_vp_xx in uniaxial flow (§1.3), sigma = Y0 + H eps_vp_xx, i.e. the effective 1D
/// plastic modulus is H itself, and the tangent modulus against total strain is E_T = E H/(E + H).
/// The Perzyna overstress d = sigma - Y satisfies d_rate = E eps_rate - (E + H) gamma d / Y, so
/// after the short transient d -> d_qs = E eps_rate Y / ((E + H) gamma), and since
/// sigma (1 + H/E) = Y0 + H eps + d exactly, sigma = sigma_ri(eps) + d E/(E + H).
void check_slow_uniaxial_loading(double hardening_modulus) {
  const double strain_rate = 1e-3, fluidity = 10.0;
  const PerzynaVonMises material = make_material(hardening_modulus, fluidity);
  const double young = material.elastic().young_modulus;
  const double initial_yield = material.parameters().yield_stress;
  const double hardening = hardening_modulus;

  DriveOptions options;
  options.time_step = 0.05;
  options.substep_factor = 0.5;
  const auto history = drive(material, StrainPath::uniaxial_stress(strain_rate, 50.0),
                             initial_point_state(material, {}), options);
  int checked = 0;
  for (const PointState& state : history) {
    const double strain = state.strain[0];
    if (strain < 2.0 * initial_yield / young) continue;  // transient decays within 1e-6 strain
    const double rate_independent =
        initial_yield + young * hardening / (young + hardening) * (strain - initial_yield / young);
    const double overstress =
        young * strain_rate * rate_independent / ((young + hardening) * fluidity);
    const double expected = rate_independent + overstress * young / (young + hardening);
    // The neglected terms (the slow drift of d_qs as Y changes) are of relative size
    // (eps_rate/gamma) E|H|/(E+H)^2 ~ 1e-5 of d; 1e-3 d bounds them with margin and still fails
    // if the overstress term were wrong by 0.1 %.
    EXPECT_NEAR(state.stress[0], expected, 1e-3 * overstress) << "strain " << strain;
    // The slow-rate limit in the form sigma = Y0 + H eps_vp_xx with eps_vp_xx = eps - sigma/E
    // taken from the state, within the overstress d.
    const double plastic_strain = strain - state.stress[0] / young;
    EXPECT_NEAR(state.stress[0], initial_yield + hardening * plastic_strain, 1.01 * overstress);
    EXPECT_NEAR(state.internal[PerzynaVonMises::kEquivalentStrain], plastic_strain, 1e-9 * strain);
    ++checked;
  }
  EXPECT_GT(checked, 500);
}

TEST(PerzynaVonMises, HardeningFollowsRateIndependentLineAtSlowRate) {
  check_slow_uniaxial_loading(0.1 * 10e6);
}

TEST(PerzynaVonMises, SofteningFollowsRateIndependentLineAtSlowRate) {
  check_slow_uniaxial_loading(-0.05 * 10e6);
}

TEST(PerzynaVonMises, SofteningStopsAtMinimumYieldStress) {
  // H = -2 MPa takes Y from 100 kPa to the 50 kPa floor after eps_vp = 0.025; loading on to a
  // plastic strain of ~0.05 must leave Y at the floor and sigma just above it (overstress
  // eps_rate E / gamma ... ~1e-4 relative at this rate).
  const PerzynaVonMises material = make_material(-2e6, 10.0, 1.0, 50e3);
  DriveOptions options;
  options.time_step = 0.05;
  const auto history = drive(material, StrainPath::uniaxial_stress(1e-3, 60.0),
                             initial_point_state(material, {}), options);
  const PointState& last = history.back();
  EXPECT_GT(last.internal[PerzynaVonMises::kEquivalentStrain], 0.04);
  EXPECT_GE(last.internal[PerzynaVonMises::kYieldStress], 50e3 * (1.0 - 1e-3));
  EXPECT_LE(last.internal[PerzynaVonMises::kYieldStress], 50e3);
  EXPECT_NEAR(last.stress[0], 50e3, 50e3 * 1e-3);
}

TEST(PerzynaVonMises, FlowVectorAndCoefficientsMatchGradientOfQ) {
  std::mt19937 generator(23);
  std::uniform_real_distribution<double> principal(-4e5, 1e5);
  const auto q = [](const SymmetricTensor& s) { return principal_invariants(s).q; };
  int checked = 0;
  while (checked < 10) {
    const SymmetricTensor stress =
        rotated_principal({principal(generator), principal(generator), principal(generator)},
                          random_rotation(generator));
    // Near theta = +-30° m2 and m3 become parallel and the projection below is ill-posed.
    if (std::abs(principal_invariants(stress).sin_3theta) > 0.95) continue;
    // Step 1 Pa on a 1e5 Pa scale: truncation (1/1e5)^2 = 1e-10, round-off 1e-15 * 1e5 / 1.
    const SymmetricTensor expected = finite_difference_gradient(q, stress, 1.0);
    const SymmetricTensor flow = PerzynaVonMises::flow_direction(stress);
    EXPECT_LT(distance(flow, expected), 1e-6 * tensor_norm(expected));
    // C1 = 0, C2 = sqrt3, C3 = 0 against the projection of the finite-difference gradient; the
    // projection amplifies the 1e-10 error by at most 1/(1 - 0.95^2) ~ 10.
    const FlowCoefficients c = PerzynaVonMises::flow_coefficients();
    const std::array<double, 3> projected =
        test_support::project_on_invariant_gradients(expected, stress);
    const double j2 = principal_invariants(stress).j2;
    EXPECT_NEAR(c.c1, projected[0], 1e-6);
    EXPECT_NEAR(c.c2, projected[1], 1e-6 * std::sqrt(3.0));
    // |m3| ~ J2, so C3 is compared at the scale sqrt3 / J2 of the other terms.
    EXPECT_NEAR(c.c3, projected[2], 1e-6 * std::sqrt(3.0) / j2);
    ++checked;
  }
  // At q = 0 there is no flow direction (and no flow).
  EXPECT_EQ(tensor_norm(PerzynaVonMises::flow_direction({-1e5, -1e5, -1e5, 0, 0, 0})), 0.0);
}

TEST(PerzynaVonMises, EquivalentStrainRateIsFluidityTimesOverstress) {
  // docs/theory.md §1.4: with m = (3/2) s/q, sqrt(2/3 e_vp:e_vp) = gamma Psi; checked against the
  // deviatoric norm of the returned strain rate computed here.
  const PerzynaVonMises material = make_material(5e5, 2.0, 1.5);
  std::mt19937 generator(2);
  const SymmetricTensor stress =
      rotated_principal({-400e3, -150e3, 20e3}, random_rotation(generator));
  const std::array<double, 2> internal = {0.0, 100e3};
  SymmetricTensor strain_rate;
  std::array<double, 2> internal_rate{};
  material.viscoplastic_rate(stress, internal, strain_rate, internal_rate);
  const double q = principal_invariants(stress).q;
  const double psi = std::pow((q - 100e3) / 100e3, 1.5);
  const double mean = (strain_rate[0] + strain_rate[1] + strain_rate[2]) / 3.0;
  SymmetricTensor deviatoric = strain_rate;
  for (int i = 0; i < 3; ++i)
    deviatoric[i] -= mean;
  const double equivalent = std::sqrt(2.0 / 3.0) * tensor_norm(deviatoric);
  EXPECT_NEAR(equivalent, 2.0 * psi, 1e-12 * psi);
  EXPECT_NEAR(internal_rate[PerzynaVonMises::kEquivalentStrain], 2.0 * psi, 1e-12 * psi);
  EXPECT_NEAR(internal_rate[PerzynaVonMises::kYieldStress], 5e5 * 2.0 * psi, 1e-12 * 5e5 * psi);
  EXPECT_NEAR(mean, 0.0, 1e-15 * equivalent);  // Von Mises flow is isochoric
}

/// |d S / d q| of the stress source S = -D:eps_vp_rate, by central differences along the
/// deviator (moving q at fixed p and Lode angle), independent of source_stiffness.
double measured_stiffness(const PerzynaVonMises& material, const SymmetricTensor& stress,
                          double yield) {
  const std::array<double, 2> internal = {0.0, yield};
  const auto source_norm = [&](double scale) {
    SymmetricTensor scaled = stress;
    const double mean = (stress[0] + stress[1] + stress[2]) / 3.0;
    for (int i = 0; i < 6; ++i)
      scaled[i] = (stress[i] - (i < 3 ? mean : 0.0)) * scale;
    for (int i = 0; i < 3; ++i)
      scaled[i] += mean;
    SymmetricTensor strain_rate;
    std::array<double, 2> internal_rate{};
    material.viscoplastic_rate(scaled, internal, strain_rate, internal_rate);
    const double shear_modulus = material.elastic().shear_modulus();
    // Isochoric flow: D:eps_vp = 2G eps_vp; its q-measure is sqrt(3/2) |2G eps_vp|.
    return std::sqrt(1.5) * 2.0 * shear_modulus * tensor_norm(strain_rate);
  };
  const double q = principal_invariants(stress).q;
  const double relative_step = 1e-6;
  return (source_norm(1.0 + relative_step) - source_norm(1.0 - relative_step)) /
         (2.0 * relative_step * q);
}

TEST(PerzynaVonMises, SourceStiffnessIsRelaxationRateOfQ) {
  const SymmetricTensor stress =
      rotated_principal({-300e3, -150e3, -100e3}, Eigen::Matrix3d::Identity());
  const double q = principal_invariants(stress).q;  // ~180 kPa: (q - Y)/Y ~ 0.8
  for (double exponent : {1.0, 2.0, 0.5}) {
    const PerzynaVonMises material = make_material(0.0, 3.0, exponent);
    const std::array<double, 2> internal = {0.0, 100e3};
    // Central differences with relative step 1e-6 of a smooth function: ~1e-10 relative.
    EXPECT_NEAR(
        material.source_stiffness(stress, internal) / measured_stiffness(material, stress, 100e3),
        1.0, 1e-6)
        << "N = " << exponent << ", q = " << q;
  }
  // N = 1: 3 G gamma / Y at any state (docs/theory.md eq. 2.7), also inside the yield surface.
  const PerzynaVonMises linear = make_material(0.0, 3.0);
  const std::array<double, 2> internal = {0.0, 100e3};
  const double expected = 3.0 * linear.elastic().shear_modulus() * 3.0 / 100e3;
  EXPECT_NEAR(linear.source_stiffness({-1e5, -1e5, -1e5, 0, 0, 0}, internal), expected,
              1e-12 * expected);
  // N < 1 near Psi = 0: the rate is capped at (q - Y)/Y = 1e-6, here N (1e-6)^(N-1) = 500 times
  // the N = 1 value.
  const PerzynaVonMises root = make_material(0.0, 3.0, 0.5);
  EXPECT_NEAR(root.source_stiffness({-1e5, -1e5, -1e5, 0, 0, 0}, internal), 500.0 * expected,
              1e-9 * 500.0 * expected);
  // Hardening stiffens the overstress relaxation: (3G + H) gamma / Y.
  const PerzynaVonMises hardening = make_material(2e6, 3.0);
  const double with_hardening = (3.0 * linear.elastic().shear_modulus() + 2e6) * 3.0 / 100e3;
  EXPECT_NEAR(hardening.source_stiffness(stress, internal), with_hardening, 1e-12 * with_hardening);
}

TEST(PerzynaVonMises, NoFlowInsideYieldSurface) {
  const PerzynaVonMises material = make_material(1e6, 5.0);
  const std::array<double, 2> internal = {0.0, 100e3};
  SymmetricTensor strain_rate;
  std::array<double, 2> internal_rate{1.0, 1.0};
  // q = 99 kPa < Y.
  material.viscoplastic_rate({-99e3, 0.0, 0.0, 0.0, 0.0, 0.0}, internal, strain_rate,
                             internal_rate);
  EXPECT_EQ(tensor_norm(strain_rate), 0.0);
  EXPECT_EQ(internal_rate[0], 0.0);
  EXPECT_EQ(internal_rate[1], 0.0);
}

}  // namespace
}  // namespace rktsph::perzyna_von_mises_test
