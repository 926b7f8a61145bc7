#include "rktsph/materials/perzyna_modified_cam_clay.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "rktsph/materials/linear_elastic.hpp"
#include "rktsph/materials/perzyna_overstress.hpp"

namespace rktsph {

PerzynaModifiedCamClay::PerzynaModifiedCamClay(double density, ElasticConstants elastic,
                                               PerzynaModifiedCamClayParameters parameters)
    : Material(density, parameters.elasticity ==
                                PerzynaModifiedCamClayParameters::Elasticity::PressureDependent
                            ? pressure_dependent_elastic(parameters, parameters.maximum_pressure)
                            : elastic),
      parameters_(parameters),
      sin_friction_angle_(std::sin(parameters.friction_angle * std::numbers::pi / 180.0)) {}

std::unique_ptr<Material> PerzynaModifiedCamClay::from_parameters(ParameterReader& reader) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  using Elasticity = PerzynaModifiedCamClayParameters::Elasticity;
  PerzynaModifiedCamClayParameters p;
  const bool pressure_dependent =
      reader.optional_word("elasticity", "constant", {"constant", "pressure_dependent"}) ==
      "pressure_dependent";
  ElasticParameters elastic{};
  if (pressure_dependent) {
    p.elasticity = Elasticity::PressureDependent;
    elastic.density = reader.required("density", 0.0, infinity, true);
  } else {
    elastic = read_elastic_parameters(reader);
  }
  p.friction_angle = reader.required("friction_angle", 0.0, 90.0, true, true);
  p.swelling_index = reader.required("swelling_index", 0.0, infinity, true);
  // lambda_c > kappa_c, otherwise the hardening factor (1 + e0)/(lambda_c - kappa_c) is not
  // positive and finite.
  p.compression_index = reader.required("compression_index", p.swelling_index, infinity, true);
  p.initial_void_ratio = reader.required("initial_void_ratio", 0.0, infinity, true);
  p.preconsolidation_pressure = reader.required("preconsolidation_pressure", 0.0, infinity, true);
  p.fluidity = reader.required("fluidity", 0.0, infinity, true);
  p.exponent = reader.optional("exponent", 1.0, 0.0, infinity, true);
  if (pressure_dependent) {
    // G from a constant nu, or a constant G: one of the two, never both (the other would be
    // silently overridden).
    const bool has_poisson = reader.has("poisson_ratio"), has_shear = reader.has("shear_modulus");
    if (has_poisson == has_shear)
      reader.reject_block(
          "elasticity: pressure_dependent needs exactly one of poisson_ratio and "
          "shear_modulus",
          "poisson_ratio in (-1, 0.5) or shear_modulus > 0");
    if (has_shear)
      p.shear_modulus = reader.required("shear_modulus", 0.0, infinity, true);
    else
      p.poisson_ratio = reader.required("poisson_ratio", -1.0, 0.5, true, true);
    // The clamp keeps K (and G with nu) away from 0 at vanishing p (a free surface, a tensile
    // state) and bounds the stiffest state, which sizes the time step.
    const double pc0 = p.preconsolidation_pressure;
    p.minimum_pressure = reader.optional("minimum_pressure", 0.01 * pc0, 0.0, infinity, true);
    p.maximum_pressure =
        reader.optional("maximum_pressure", 4.0 * pc0, p.minimum_pressure, infinity, true);
  }
  return std::make_unique<PerzynaModifiedCamClay>(elastic.density, elastic.elastic, p);
}

ElasticConstants PerzynaModifiedCamClay::pressure_dependent_elastic(
    const PerzynaModifiedCamClayParameters& p, double pressure) {
  const double clamped = std::clamp(pressure, p.minimum_pressure, p.maximum_pressure);
  // eq. 1.10a: the slope kappa_c of the unloading line e = e_kappa - kappa_c ln p' gives
  // dp/d(eps_v, compression positive) = (1 + e) p / kappa_c, with e held at e0.
  const double bulk = (1.0 + p.initial_void_ratio) * clamped / p.swelling_index;
  ElasticConstants constants;
  if (std::isnan(p.shear_modulus)) {
    // eq. 1.10b with constant nu: E = 3K(1 - 2nu).
    constants.poisson_ratio = p.poisson_ratio;
    constants.young_modulus = 3.0 * bulk * (1.0 - 2.0 * p.poisson_ratio);
  } else {
    // eq. 1.10b with constant G: E = 9KG / (3K + G), nu = (3K - 2G) / (2(3K + G)).
    const double shear = p.shear_modulus;
    constants.young_modulus = 9.0 * bulk * shear / (3.0 * bulk + shear);
    constants.poisson_ratio = (3.0 * bulk - 2.0 * shear) / (2.0 * (3.0 * bulk + shear));
  }
  return constants;
}

ElasticConstants PerzynaModifiedCamClay::elastic_at(const SymmetricTensor& stress) const {
  if (!stress_dependent_elasticity()) return elastic();
  return pressure_dependent_elastic(parameters_, mean_pressure(stress));
}

std::vector<std::string> PerzynaModifiedCamClay::internal_names() const {
  return {"eps_vp", "preconsolidation_pressure"};
}

void PerzynaModifiedCamClay::initial_internal(std::span<double> internal) const {
  internal[kEquivalentStrain] = 0.0;
  internal[kPreconsolidationPressure] = parameters_.preconsolidation_pressure;
}

double PerzynaModifiedCamClay::hardening_factor() const {
  return (1.0 + parameters_.initial_void_ratio) /
         (parameters_.compression_index - parameters_.swelling_index);
}

double PerzynaModifiedCamClay::critical_state_ratio(double sin_3theta) const {
  return 6.0 * sin_friction_angle_ / (3.0 - sin_friction_angle_ * sin_3theta);
}

double PerzynaModifiedCamClay::yield_function(const StressInvariants& invariants,
                                              double preconsolidation_pressure) const {
  const double ratio = critical_state_ratio(invariants.sin_3theta);
  const double p = invariants.pressure;
  return invariants.q * invariants.q + ratio * ratio * p * (p - preconsolidation_pressure);
}

double PerzynaModifiedCamClay::overstress(const SymmetricTensor& stress,
                                          std::span<const double> internal) const {
  const double pc = internal[kPreconsolidationPressure];
  return macaulay_power(yield_function(stress_invariants(stress), pc) / (pc * pc),
                        parameters_.exponent);
}

// Why not the gradient of g = f / pc (docs/theory.md eq. 1.8): its theta part is
// (2 M p (p - pc) / pc) dM/dstress, and dM/dstress ~ 1/sqrt(J2) near the hydrostatic axis, so m
// blows up there at any p other than 0 and pc, which a state crossing the axis (isotropic loading)
// meets. The regular potential
//   g' = q^2 / M^2 + p (p - pc)   (zero on the same ellipse)
// has dg'/dstress = (2q/M^2) dq + (2p - pc) dp - (2 q^2 / M^3) dM. Scaled by M^2 / pc (a positive
// factor, so the direction of flow is unchanged) it gives
//   m = [2q dq + M^2 (2p - pc) dp - (2 q^2 / M) dM] / pc.
// The q and p terms are those of the thesis's m. On the ellipse q^2 = -M^2 p (p - pc), so the M
// term equals the thesis's 2 M p (p - pc) / pc dM (eq. 1.10): the two vectors coincide where the
// flow starts. Off the ellipse the M term is ~ q^2 / sqrt(J2) ~ sqrt(J2) and vanishes on the axis.
FlowCoefficients PerzynaModifiedCamClay::flow_coefficients(const StressInvariants& invariants,
                                                           double preconsolidation_pressure) const {
  const double pc = preconsolidation_pressure;
  const double p = invariants.pressure;
  const double ratio = critical_state_ratio(invariants.sin_3theta);
  FlowCoefficients c;
  // C1 = M^2 (2p - pc)/pc times dp/dI1 = -1/3.
  c.c1 = -ratio * ratio * (2.0 * p - pc) / (3.0 * pc);
  // C2 (q part) = 2q dq/dsqrtJ2 / pc = 6 sqrtJ2 / pc, as q = sqrt3 sqrtJ2.
  const double root_j2 = std::sqrt(invariants.j2);
  c.c2 = 6.0 * root_j2 / pc;
  if (!invariants.lode_defined) return c;
  // The theta term is -(2 q^2 / (M pc)) dM/dtheta dtheta/dstress with
  // dM/dtheta = 18 sin^2(phi) cos 3theta / (3 - sin(phi) sin 3theta)^2. Its cos 3theta cancels the
  // tan 3theta and 1/cos 3theta of C2 and C3 (eq. 1.9), so nothing is singular at +-30°.
  // theta_factor is (dg/dtheta) / (2 cos 3theta) in the notation of invariants.hpp.
  const double denominator = 3.0 - sin_friction_angle_ * invariants.sin_3theta;
  const double q_squared = 3.0 * invariants.j2;
  const double theta_factor = -q_squared / (ratio * pc) * 18.0 * sin_friction_angle_ *
                              sin_friction_angle_ / (denominator * denominator);
  // C2 gains -(sin 3theta / sqrtJ2) 2 theta_factor ~ sqrtJ2, and C3 = -sqrt3 J2^(-3/2)
  // theta_factor ~ 1/sqrtJ2 multiplies m3 ~ J2: both terms of m vanish like sqrtJ2 on the axis.
  c.c2 -= invariants.sin_3theta / root_j2 * 2.0 * theta_factor;
  c.c3 = -std::sqrt(3.0) / (invariants.j2 * root_j2) * theta_factor;
  return c;
}

SymmetricTensor PerzynaModifiedCamClay::flow_direction(const SymmetricTensor& stress,
                                                       double preconsolidation_pressure) const {
  const StressInvariants invariants = stress_invariants(stress);
  return flow_vector(invariants, flow_coefficients(invariants, preconsolidation_pressure));
}

void PerzynaModifiedCamClay::viscoplastic_rate(const SymmetricTensor& stress,
                                               std::span<const double> internal,
                                               SymmetricTensor& strain_rate,
                                               std::span<double> internal_rate) const {
  const double pc = internal[kPreconsolidationPressure];
  const StressInvariants invariants = stress_invariants(stress);
  const double psi =
      macaulay_power(yield_function(invariants, pc) / (pc * pc), parameters_.exponent);
  strain_rate.fill(0.0);
  internal_rate[kEquivalentStrain] = 0.0;
  internal_rate[kPreconsolidationPressure] = 0.0;
  if (psi <= 0.0) return;
  const double flow_magnitude = parameters_.fluidity * psi;
  const SymmetricTensor direction = flow_vector(invariants, flow_coefficients(invariants, pc));
  for (int i = 0; i < 6; ++i)
    strain_rate[i] = flow_magnitude * direction[i];
  internal_rate[kEquivalentStrain] = equivalent_strain_rate(strain_rate);
  // The thesis's law with compression-positive volumetric strain, turned to tension positive
  // (docs/theory.md §1.5).
  internal_rate[kPreconsolidationPressure] = -hardening_factor() * pc * trace(strain_rate);
}

PerzynaModifiedCamClay::SourceState PerzynaModifiedCamClay::source(const SourceState& state) const {
  const std::array<double, 2> internal = {0.0, state.preconsolidation_pressure};
  std::array<double, 2> internal_rate{};
  SymmetricTensor strain_rate;
  viscoplastic_rate(state.stress, internal, strain_rate, internal_rate);
  SymmetricTensor stress_rate = apply_elastic_stiffness(elastic_at(state.stress), strain_rate);
  for (double& component : stress_rate)
    component = -component;
  return {stress_rate, internal_rate[kPreconsolidationPressure]};
}

namespace {
/// Euclidean norm of (stress, pc) with a tensor norm for the stress; both parts are in Pa.
double state_norm(const SymmetricTensor& stress, double preconsolidation_pressure) {
  return std::sqrt(double_contraction(stress, stress) +
                   preconsolidation_pressure * preconsolidation_pressure);
}
}  // namespace

double PerzynaModifiedCamClay::source_stiffness(const SymmetricTensor& stress,
                                                std::span<const double> internal) const {
  // The source is -gamma Psi (D:m, A pc tr m) with A = hardening_factor(): it moves the state
  // along d = (D:m, A pc tr m). Its Jacobian is dominated by the rank-one part
  // -gamma d (x) dPsi/dy, whose eigenvalue is -gamma dPsi/dy . d, so the difference quotient of
  // the source along d measures the relaxation rate. A second quotient along (D:m, 0), the stress
  // alone, is also taken: on the dry side (p < pc/2) the hardening term cancels part of the
  // first one, while the stress still relaxes at its own rate. The larger of the two is returned.
  const double pc = internal[kPreconsolidationPressure];
  const SymmetricTensor direction = flow_direction(stress, pc);
  const SymmetricTensor stress_direction = apply_elastic_stiffness(elastic_at(stress), direction);
  const double hardening_direction = hardening_factor() * pc * trace(direction);
  const double step = kStiffnessStepRatio * pc;
  const SourceState base{stress, pc};
  const SourceState base_source = source(base);

  auto quotient = [&](double pc_direction) {
    const double length = state_norm(stress_direction, pc_direction);
    if (!(length > 0.0)) return 0.0;
    SourceState moved = base;
    for (int i = 0; i < 6; ++i)
      moved.stress[i] += step * stress_direction[i] / length;
    moved.preconsolidation_pressure += step * pc_direction / length;
    const SourceState moved_source = source(moved);
    SymmetricTensor stress_change;
    for (int i = 0; i < 6; ++i)
      stress_change[i] = moved_source.stress[i] - base_source.stress[i];
    return state_norm(stress_change, moved_source.preconsolidation_pressure -
                                         base_source.preconsolidation_pressure) /
           step;
  };
  return std::max(quotient(hardening_direction), quotient(0.0));
}

}  // namespace rktsph
