// The stress update of one material point alone (materials/overstress_integrator.hpp): Perzyna
// relaxation of a held overstress against the closed-form exponential (docs/theory.md §1.3, N = 1,
// H = 0), the sub-step rule of docs/theory.md eq. 2.7 through the exact RK4 amplification of a
// linear source, the frozen flux against the additive split (§2.1, §2.8) and the tension cut-off
// (§1.7). The stiffnesses and the expected values are written here from E and nu, not taken from
// the code.
#include "rktsph/materials/overstress_integrator.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

#include "rktsph/materials/linear_elastic.hpp"
#include "rktsph/materials/perzyna_modified_cam_clay.hpp"
#include "rktsph/materials/perzyna_von_mises.hpp"

namespace rktsph::overstress_integrator_test {
namespace {

constexpr double kYoung = 1.0e7, kPoisson = 0.3;
constexpr double kShear = kYoung / (2.0 * (1.0 + kPoisson));
constexpr double kLambda = kYoung * kPoisson / ((1.0 + kPoisson) * (1.0 - 2.0 * kPoisson));
constexpr double kYield = 1.0e4;    // Y [Pa]
constexpr double kFluidity = 10.0;  // gamma [1/s]
constexpr double kNoCutOff = std::numeric_limits<double>::infinity();

PerzynaVonMises von_mises(double tension_cutoff = kNoCutOff, double yield = kYield) {
  PerzynaVonMisesParameters parameters;
  parameters.yield_stress = yield;
  parameters.hardening_modulus = 0.0;
  parameters.fluidity = kFluidity;
  parameters.exponent = 1.0;
  parameters.minimum_yield_stress = 0.01 * yield;
  parameters.tension_cutoff = tension_cutoff;
  return PerzynaVonMises(2000.0, ElasticConstants{kYoung, kPoisson}, parameters);
}

double& at(CondensedStiffness& d, int row, int column) {
  return d[static_cast<std::size_t>(row * CarriedStress::kMax + column)];
}

// Plane strain, carried in the order xx, yy, xy, zz: nothing is stress-free, so D is Hooke's law
// restricted to these components (lambda + 2G, lambda; G on the engineering shear).
struct Setting {
  CarriedStress carried;
  CondensedStiffness stiffness{};
};

Setting plane_strain() {
  Setting s;
  s.carried.count = 4;
  s.carried.slot = {0, 1, 3, 2, 0, 0};
  s.carried.shear_factor = {1.0, 1.0, 2.0, 1.0, 0.0, 0.0};
  for (int r : {0, 1, 3})
    for (int c : {0, 1, 3})
      at(s.stiffness, r, c) = r == c ? kLambda + 2.0 * kShear : kLambda;
  at(s.stiffness, 2, 2) = kShear;
  return s;
}

// Plane stress, carried xx, yy, xy: D = E'/(1 - nu^2) [[1, nu, 0], [nu, 1, 0], [0, 0, (1-nu)/2]].
Setting plane_stress() {
  Setting s;
  s.carried.count = 3;
  s.carried.slot = {0, 1, 3, 0, 0, 0};
  s.carried.shear_factor = {1.0, 1.0, 2.0, 0.0, 0.0, 0.0};
  const double modulus = kYoung / (1.0 - kPoisson * kPoisson);
  at(s.stiffness, 0, 0) = at(s.stiffness, 1, 1) = modulus;
  at(s.stiffness, 0, 1) = at(s.stiffness, 1, 0) = modulus * kPoisson;
  at(s.stiffness, 2, 2) = modulus * (1.0 - kPoisson) / 2.0;
  return s;
}

// The 1D bar, carried xx only: D = E.
Setting bar() {
  Setting s;
  s.carried.count = 1;
  s.carried.shear_factor[0] = 1.0;
  at(s.stiffness, 0, 0) = kYoung;
  return s;
}

SourceIntegration integration(double substep_factor, bool frozen_flux = true) {
  SourceIntegration options;
  options.substep_factor = substep_factor;
  options.max_substeps = 100000;
  options.frozen_flux = frozen_flux;
  return options;
}

// Pure shear in plane strain: q = sqrt(3) tau, and with N = 1, H = 0 the overstress relaxes as
// q' = -3 G gamma (q - Y)/Y + sqrt(3) R_tau: linear in q - Y at the rate lambda = 3 G gamma / Y.
constexpr double kRelaxationRate = 3.0 * kShear * kFluidity / kYield;

struct ShearResult {
  double q = 0.0;
  std::array<double, 4> sigma{};
  std::array<double, 2> kappa{};
};

ShearResult shear(double q0, double rate_tau, double interval, SourceIntegration options) {
  const PerzynaVonMises material = von_mises();
  const Setting s = plane_strain();
  const OverstressIntegrator integrator(material, s.carried, s.stiffness, options);
  ShearResult result;
  result.sigma = {0.0, 0.0, q0 / std::sqrt(3.0), 0.0};
  material.initial_internal(result.kappa);
  const std::array<double, 4> rate{0.0, 0.0, rate_tau, 0.0};
  integrator.advance(rate.data(), interval, result.sigma.data(), result.kappa.data());
  result.q = std::sqrt(3.0) * std::abs(result.sigma[2]);
  return result;
}

TEST(OverstressIntegrator, HeldOverstressRelaxesToTheYieldSurfaceAtThePerzynaRate) {
  // The elastic predictor put q at 2 Y and the strain is then held (R = 0):
  //   q - Y = (q0 - Y) exp(-lambda t),  eps_vp = (q0 - q) / (3 G)   (the stress lost, over 3 G).
  // Fine sub-steps (lambda delta = 0.01): RK4's error, (lambda delta)^5/120 per sub-step, is
  // below 1e-12 of the overstress.
  const double q0 = 2.0 * kYield;
  for (double lambda_t : {0.25, 1.0, 4.0}) {
    const double t = lambda_t / kRelaxationRate;
    const ShearResult r = shear(q0, 0.0, t, integration(0.01));
    const double expected = (q0 - kYield) * std::exp(-lambda_t);
    EXPECT_NEAR((r.q - kYield) / expected, 1.0, 1e-9) << "lambda t = " << lambda_t;
    EXPECT_NEAR(r.kappa[PerzynaVonMises::kEquivalentStrain], (q0 - r.q) / (3.0 * kShear),
                1e-9 * (q0 - kYield) / (3.0 * kShear));
    EXPECT_EQ(r.kappa[PerzynaVonMises::kYieldStress], kYield);  // H = 0
    // Deviatoric flow in pure shear leaves the normal stresses at zero.
    EXPECT_EQ(r.sigma[0], 0.0);
    EXPECT_EQ(r.sigma[1], 0.0);
    EXPECT_EQ(r.sigma[3], 0.0);
  }
  // Long after, the point sits on the yield surface.
  const ShearResult settled = shear(q0, 0.0, 40.0 / kRelaxationRate, integration(0.01));
  EXPECT_NEAR(settled.q, kYield, 1e-12 * kYield);
}

TEST(OverstressIntegrator, SubStepsFollowTheRuleOfEq27) {
  // On a linear source one RK4 sub-step multiplies the overstress by the degree-4 Taylor
  // polynomial P(x) = 1 - x + x^2/2 - x^3/6 + x^4/24 of exp(-x), x = lambda delta, so after the
  // interval q - Y = (q0 - Y) P(lambda tau / m)^m with m = ceil(lambda tau / 0.5) (the step's
  // factor; source_stiffness is exactly lambda here). One sub-step more or less would differ by
  // far more than the tolerance.
  const double q0 = 2.0 * kYield;
  auto polynomial = [](double x) {
    return 1.0 - x + x * x / 2.0 - x * x * x / 6.0 + x * x * x * x / 24.0;
  };
  for (double lambda_t : {0.3, 1.7, 6.2}) {
    const double t = lambda_t / kRelaxationRate;
    const int m = static_cast<int>(std::ceil(lambda_t / 0.5));
    const double expected = (q0 - kYield) * std::pow(polynomial(lambda_t / m), m);
    const double other = (q0 - kYield) * std::pow(polynomial(lambda_t / (m + 1)), m + 1);
    const ShearResult r = shear(q0, 0.0, t, integration(0.5));
    EXPECT_NEAR(r.q - kYield, expected, 1e-11 * kYield) << "m = " << m;
    EXPECT_GT(std::abs(expected - other), 1e-9 * kYield) << "m = " << m;
    // And the rule's sub-steps stay within a few per mille of the exponential relaxation.
    EXPECT_NEAR((r.q - kYield) / ((q0 - kYield) * std::exp(-lambda_t)), 1.0, 5e-3);
  }
  EXPECT_EQ(substep_count(1.0, 2.3, 0.5, 1000), 5);
  EXPECT_EQ(substep_count(1.0, 0.0, 0.5, 1000), 1);
  EXPECT_EQ(substep_count(1.0, 1e12, 0.5, 1000), 1000);
  EXPECT_EQ(substep_count(1.0, kNoCutOff, 0.5, 1000), 1000);
}

TEST(OverstressIntegrator, OneLargeSubStepUndershootsTheYieldSurface) {
  // Why the step's factor is 0.5 and not 2.5 (docs/theory.md §2.1): at x = lambda delta = 2.3 the
  // second and fourth RK4 stages, y (1 - x/2) and y (1 - x), lie inside the elastic domain where
  // the Macaulay bracket gives no source, so one sub-step gives y (1 - 3x/6) = -0.15 y for the
  // overstress y = q - Y (with the exact step, e^-2.3 y = 0.10 y).
  const double q0 = 2.0 * kYield;
  const ShearResult r = shear(q0, 0.0, 2.3 / kRelaxationRate, integration(2.5));
  EXPECT_NEAR(r.q - kYield, -0.15 * (q0 - kYield), 1e-9 * kYield);
}

TEST(OverstressIntegrator, UniaxialBarRelaxesWithTheYoungModulus) {
  // The bar carries sigma_xx only (the lateral strains are condensed into D = E), so
  // sigma - Y = (sigma0 - Y) exp(-E gamma t / Y).
  const PerzynaVonMises material = von_mises();
  const Setting s = bar();
  const OverstressIntegrator integrator(material, s.carried, s.stiffness, integration(0.01));
  const double rate = kYoung * kFluidity / kYield;
  const double t = 1.5 / rate;
  double sigma = 1.5 * kYield, zero = 0.0;
  std::array<double, 2> kappa{};
  material.initial_internal(kappa);
  integrator.advance(&zero, t, &sigma, kappa.data());
  EXPECT_NEAR((sigma - kYield) / (0.5 * kYield * std::exp(-1.5)), 1.0, 1e-9);
}

TEST(OverstressIntegrator, FrozenFluxTendsToTheOverstressOfItsRate) {
  // From the yield surface under a constant shear stress rate R: with R frozen in the ODE,
  // q - Y = (sqrt(3) R / lambda)(1 - exp(-lambda t)). The additive split integrates the source
  // alone from the start, where it is zero, and adds t R: an elastic update.
  const double rate_tau = 1.0e5;  // [Pa/s]
  const double t = 2.0 / kRelaxationRate;
  const ShearResult frozen = shear(kYield, rate_tau, t, integration(0.01));
  const double steady = std::sqrt(3.0) * rate_tau / kRelaxationRate;
  EXPECT_NEAR((frozen.q - kYield) / (steady * (1.0 - std::exp(-2.0))), 1.0, 1e-9);
  const ShearResult additive = shear(kYield, rate_tau, t, integration(0.01, false));
  EXPECT_NEAR(additive.sigma[2], kYield / std::sqrt(3.0) + t * rate_tau, 1e-12 * kYield);
}

TEST(OverstressIntegrator, PathInsideTheElasticDomainIsExactlyElastic) {
  // Start and elastic predictor below the yield surface: sigma += t R, kappa unchanged.
  const ShearResult r = shear(0.2 * kYield, 1.0e3, 1.0, integration(0.5));
  EXPECT_NEAR(r.sigma[2], 0.2 * kYield / std::sqrt(3.0) + 1.0e3, 1e-12 * kYield);
  EXPECT_EQ(r.kappa[PerzynaVonMises::kEquivalentStrain], 0.0);
}

TEST(OverstressIntegrator, TensionCutOffSetsTheMeanStressToTheLimit) {
  // docs/theory.md eq. 1.7: the carried normal stresses move alike by 3 (p - limit)/m. The yield
  // stress is far above these stresses, so only the cut-off acts.
  const double limit = 1.0e3;
  const PerzynaVonMises material = von_mises(limit, 1.0e9);
  std::array<double, 2> kappa{};
  material.initial_internal(kappa);
  {
    // Plane strain (m = 3): p = (9 + 3 + 6)/3 kPa = 6 kPa is shifted down by 5 kPa on xx, yy, zz;
    // every value is a small integer, so p equals the limit to the last bit.
    const Setting s = plane_strain();
    const OverstressIntegrator integrator(material, s.carried, s.stiffness, integration(0.5));
    std::array<double, 4> sigma{9.0e3, 3.0e3, 5.0e2, 6.0e3};
    integrator.cut_tension(sigma.data());
    EXPECT_EQ((sigma[0] + sigma[1] + sigma[3]) / 3.0, limit);
    EXPECT_EQ(sigma[0], 4.0e3);
    EXPECT_EQ(sigma[1], -2.0e3);
    EXPECT_EQ(sigma[2], 5.0e2);  // shear kept
    EXPECT_EQ(sigma[3], 1.0e3);
    // Through advance, after an elastic rate (the cut-off follows the source integration).
    std::array<double, 4> start{0.0, 0.0, 5.0e2, 0.0};
    const std::array<double, 4> rate{9.0e3, 3.0e3, 0.0, 6.0e3};
    integrator.advance(rate.data(), 1.0, start.data(), kappa.data());
    EXPECT_EQ(start, sigma);
    // Below the limit nothing moves.
    std::array<double, 4> below{1.0e3, -2.0e3, 5.0e2, 0.0};
    const std::array<double, 4> copy = below;
    integrator.cut_tension(below.data());
    EXPECT_EQ(below, copy);
  }
  {
    // Plane stress (m = 2): sigma_zz = 0 is not carried, xx and yy take 3 (p - limit)/2 each.
    const Setting s = plane_stress();
    const OverstressIntegrator integrator(material, s.carried, s.stiffness, integration(0.5));
    std::array<double, 3> sigma{8.0e3, 4.0e3, 1.0e3};
    integrator.cut_tension(sigma.data());
    EXPECT_NEAR((sigma[0] + sigma[1]) / 3.0, limit, 1e-12 * limit);
    EXPECT_NEAR(sigma[0] - sigma[1], 4.0e3, 1e-12 * limit);
    EXPECT_EQ(sigma[2], 1.0e3);
  }
  {
    // The bar (m = 1): sigma_xx = 3 limit.
    const Setting s = bar();
    const OverstressIntegrator integrator(material, s.carried, s.stiffness, integration(0.5));
    double sigma = 7.0e3;
    integrator.cut_tension(&sigma);
    EXPECT_NEAR(sigma, 3.0 * limit, 1e-12 * limit);
  }
  {
    // Without a cut-off (the default, +infinity) tension is kept.
    const PerzynaVonMises unlimited = von_mises(kNoCutOff, 1.0e9);
    const Setting s = bar();
    const OverstressIntegrator integrator(unlimited, s.carried, s.stiffness, integration(0.5));
    double sigma = 7.0e3;
    integrator.cut_tension(&sigma);
    EXPECT_EQ(sigma, 7.0e3);
  }
}

TEST(OverstressIntegrator, ElasticMaterialAdvancesByTheRate) {
  const LinearElastic material(2000.0, ElasticConstants{kYoung, kPoisson});
  const Setting s = plane_strain();
  const OverstressIntegrator integrator(material, s.carried, s.stiffness, integration(0.5));
  std::array<double, 4> sigma{1.0, 2.0, 3.0, 4.0};
  const std::array<double, 4> rate{8.0, 4.0, 2.0, 1.0};
  integrator.advance(rate.data(), 0.5, sigma.data(), nullptr);
  EXPECT_EQ(sigma, (std::array<double, 4>{5.0, 4.0, 4.0, 4.5}));
}

// Stress-dependent elasticity (Modified Cam-Clay, K = (1 + e0) p / kappa, docs/theory.md eqs.
// 1.10a-1.10c) in plane strain: the step's flux rate is D(p_max) : eps_dot; the integrator must
// recover eps_dot and follow the swelling line ln(p / p0) = -(1 + e0) eps_v / kappa with the
// tangent D, not the stiffest one it was given.
CondensedStiffness plane_strain_of(const ElasticConstants& elastic) {
  CondensedStiffness d{};
  const double lambda = elastic.lame_lambda(), shear = elastic.shear_modulus();
  for (int r : {0, 1, 3})
    for (int c : {0, 1, 3})
      at(d, r, c) = r == c ? lambda + 2.0 * shear : lambda;
  at(d, 2, 2) = shear;
  return d;
}

TEST(OverstressIntegrator, StressDependentElasticityFollowsTheSwellingLine) {
  constexpr double kappa = 0.05, e0 = 1.0, pc0 = 2e5;
  PerzynaModifiedCamClayParameters parameters;
  parameters.friction_angle = 25.0;
  parameters.compression_index = 0.2;
  parameters.swelling_index = kappa;
  parameters.initial_void_ratio = e0;
  parameters.preconsolidation_pressure = pc0;
  parameters.fluidity = 100.0;
  parameters.elasticity = PerzynaModifiedCamClayParameters::Elasticity::PressureDependent;
  parameters.poisson_ratio = 0.25;
  parameters.minimum_pressure = 0.01 * pc0;
  parameters.maximum_pressure = 4.0 * pc0;
  const PerzynaModifiedCamClay clay(1800.0, ElasticConstants{}, parameters);
  Setting s = plane_strain();
  s.stiffness = plane_strain_of(clay.elastic());
  const OverstressIntegrator integrator(clay, s.carried, s.stiffness, SourceIntegration{},
                                        plane_strain_of);
  // Isotropic swelling (eps_zz is carried in plane strain, so the test imposes it too).
  const double rate = 1e-3, interval = 0.1;
  double strain[4] = {rate, rate, 0.0, rate};  // isotropic expansion: eps_zz carried as well
  double flux[4];
  for (int r = 0; r < 4; ++r) {
    flux[r] = 0.0;
    for (int c = 0; c < 4; ++c)
      flux[r] += at(s.stiffness, r, c) * strain[c];
  }
  double sigma[4] = {-pc0, -pc0, 0.0, -pc0};
  double kappa_state[2] = {0.0, pc0};
  for (int step = 1; step <= 100; ++step) {
    integrator.advance(flux, interval, sigma, kappa_state);
    const double volumetric_strain = 3.0 * rate * interval * step;
    const double expected = pc0 * std::exp(-(1.0 + e0) * volumetric_strain / kappa);
    const double p = -(sigma[0] + sigma[1] + sigma[3]) / 3.0;
    // RK4 on a smooth linear ODE, each interval a 0.6 % change of p: ~1e-12 relative.
    ASSERT_NEAR(p / expected, 1.0, 1e-9) << "step " << step;
  }
  EXPECT_EQ(kappa_state[0], 0.0);  // inside the ellipse throughout: no flow
  EXPECT_NEAR(sigma[2], 0.0, 1e-9);
}

}  // namespace
}  // namespace rktsph::overstress_integrator_test
