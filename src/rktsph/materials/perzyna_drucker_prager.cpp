#include "rktsph/materials/perzyna_drucker_prager.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rktsph/materials/linear_elastic.hpp"
#include "rktsph/materials/perzyna_overstress.hpp"

namespace rktsph {

const std::vector<std::string>& cone_matching_words() {
  static const std::vector<std::string> words = {"plane_strain", "compression", "extension"};
  return words;
}

PerzynaDruckerPrager::PerzynaDruckerPrager(double density, ElasticConstants elastic,
                                           PerzynaDruckerPragerParameters parameters)
    : Material(density, elastic), parameters_(parameters) {}

std::unique_ptr<Material> PerzynaDruckerPrager::from_parameters(ParameterReader& reader) {
  const ElasticParameters elastic = read_elastic_parameters(reader);
  PerzynaDruckerPragerParameters p;
  const std::string matching =
      reader.optional_word("matching", cone_matching_words().front(), cone_matching_words());
  const auto index =
      std::find(cone_matching_words().begin(), cone_matching_words().end(), matching) -
      cone_matching_words().begin();
  p.matching = static_cast<ConeMatching>(index);
  // F0 defaults to k0, the strength in q at p = 0 of the initial cone.
  p.strength = read_frictional_parameters(reader, [&](const FrictionalParameters& s) {
    return matched_cone(p.matching, s.cohesion, radians(s.friction_angle),
                        radians(s.dilatancy_angle))
        .intercept;
  });
  return std::make_unique<PerzynaDruckerPrager>(elastic.density, elastic.elastic, p);
}

std::vector<std::string> PerzynaDruckerPrager::internal_names() const {
  return {"eps_vp", "cohesion", "friction_angle"};
}

void PerzynaDruckerPrager::initial_internal(std::span<double> internal) const {
  initial_frictional_internal(parameters_.strength, internal);
}

DruckerPragerCone PerzynaDruckerPrager::matched_cone(ConeMatching matching, double cohesion,
                                                     double friction_angle,
                                                     double dilatancy_angle) {
  const double sin_phi = std::sin(friction_angle);
  const double cos_phi = std::cos(friction_angle);
  const double sin_psi = std::sin(dilatancy_angle);
  DruckerPragerCone cone;
  switch (matching) {
    case ConeMatching::PlaneStrain: {
      // Eq. 1.12: the plane-strain limit state (eps_zz^vp = 0) of the cone and its potential
      // equals (sigma1 - sigma3)/2 = P sin(phi) + c cos(phi) and has the Mohr–Coulomb dilatancy
      // eps_v/(eps1 - eps3) = sin(psi).
      const double root = std::sqrt(3.0 + sin_psi * sin_psi);
      const double factor = 3.0 * root / (3.0 + sin_phi * sin_psi);
      cone.slope = factor * sin_phi;
      cone.intercept = factor * cohesion * cos_phi;
      cone.dilatancy_slope = 3.0 * sin_psi / root;
      break;
    }
    case ConeMatching::Compression:
      cone.slope = 6.0 * sin_phi / (3.0 - sin_phi);
      cone.intercept = 6.0 * cohesion * cos_phi / (3.0 - sin_phi);
      cone.dilatancy_slope = 6.0 * sin_psi / (3.0 - sin_psi);
      break;
    case ConeMatching::Extension:
      cone.slope = 6.0 * sin_phi / (3.0 + sin_phi);
      cone.intercept = 6.0 * cohesion * cos_phi / (3.0 + sin_phi);
      cone.dilatancy_slope = 6.0 * sin_psi / (3.0 + sin_psi);
      break;
  }
  return cone;
}

DruckerPragerCone PerzynaDruckerPrager::cone(std::span<const double> internal) const {
  const FrictionalStrength strength = current_strength(parameters_.strength, internal);
  return matched_cone(parameters_.matching, strength.cohesion, strength.friction_angle,
                      strength.dilatancy_angle);
}

double PerzynaDruckerPrager::yield_function(const SymmetricTensor& stress,
                                            std::span<const double> internal) const {
  const DruckerPragerCone c = cone(internal);
  return von_mises_stress(stress) - c.slope * mean_pressure(stress) - c.intercept;
}

double PerzynaDruckerPrager::cutoff_function(const SymmetricTensor& stress,
                                             std::span<const double> internal) const {
  const FrictionalStrength strength = current_strength(parameters_.strength, internal);
  return -mean_pressure(stress) - strength.tension_limit;
}

bool PerzynaDruckerPrager::flows(const SymmetricTensor& stress,
                                 std::span<const double> internal) const {
  return yield_function(stress, internal) > 0.0 || cutoff_function(stress, internal) > 0.0;
}

void PerzynaDruckerPrager::viscoplastic_rate(const SymmetricTensor& stress,
                                             std::span<const double> internal,
                                             SymmetricTensor& strain_rate,
                                             std::span<double> internal_rate) const {
  const FrictionalParameters& strength_parameters = parameters_.strength;
  const FrictionalStrength strength = current_strength(strength_parameters, internal);
  const DruckerPragerCone c = matched_cone(parameters_.matching, strength.cohesion,
                                           strength.friction_angle, strength.dilatancy_angle);
  const StressInvariants invariants = stress_invariants(stress);
  const double cone_function = invariants.q - c.slope * invariants.pressure - c.intercept;
  const double cutoff = -invariants.pressure - strength.tension_limit;
  const double scale = strength_parameters.reference_stress;
  const double exponent = strength_parameters.exponent;
  const double cone_rate =
      strength_parameters.fluidity * macaulay_power(cone_function / scale, exponent);
  const double cutoff_rate =
      strength_parameters.fluidity * macaulay_power(cutoff / scale, exponent);
  strain_rate.fill(0.0);
  double volumetric = 0.0;  // the rate of each normal component from the I terms
  if (cone_rate > 0.0) {
    // (3/2) s / max(q, F): the unit deviatoric direction of g on the regular part of the cone;
    // beyond the apex (F > q) it shrinks with q, so that the deviator decays to the axis instead
    // of overshooting it (docs/theory.md eq. 1.14). At q = 0 the deviator is zero.
    const double deviatoric_factor = 1.5 * cone_rate / std::max(invariants.q, cone_function);
    for (int i = 0; i < 6; ++i)
      strain_rate[i] = deviatoric_factor * invariants.deviator[i];
    volumetric += cone_rate * c.dilatancy_slope / 3.0;
  }
  // The cut-off flows along its own normal dF_t/dstress = I/3 (associated, eq. 1.10c).
  if (cutoff_rate > 0.0) volumetric += cutoff_rate / 3.0;
  for (int i = 0; i < 3; ++i)
    strain_rate[i] += volumetric;
  frictional_internal_rates(strength_parameters, internal, equivalent_strain_rate(strain_rate),
                            internal_rate);
}

double PerzynaDruckerPrager::source_stiffness(const SymmetricTensor& stress,
                                              std::span<const double> internal) const {
  // The cone's overstress F relaxes as -(dF/dstress : D : m + hardening) gamma Psi, with
  // dF/dstress : D : m = 3G + K M M_g on the regular cone (docs/theory.md eq. 1.15); the cut-off's
  // as -K gamma Psi_t. Their sum bounds the relaxation rate where both act (the apex).
  const FrictionalParameters& strength_parameters = parameters_.strength;
  const FrictionalStrength strength = current_strength(strength_parameters, internal);
  const DruckerPragerCone c = matched_cone(parameters_.matching, strength.cohesion,
                                           strength.friction_angle, strength.dilatancy_angle);
  const double scale = strength_parameters.reference_stress;
  const double exponent = strength_parameters.exponent;
  const auto slope = [&](double function) {
    const double relative = std::max(function / scale, kOverstressFloor);
    return exponent == 1.0 ? 1.0 : exponent * std::pow(relative, exponent - 1.0);
  };
  const double pressure = mean_pressure(stress);
  const double bulk = elastic().bulk_modulus();
  // Hardening raises the strength M p + k as the flow goes on, by dk/dc H_c and
  // d(M p + k)/dphi H_phi per unit equivalent strain; as for perzyna_von_mises only hardening
  // (not softening) is added, so that the estimate stays an upper bound.
  const double intercept_per_cohesion =
      matched_cone(parameters_.matching, 1.0, strength.friction_angle, strength.dilatancy_angle)
          .intercept;
  const double step = 1e-6;  // [rad]: central difference of a smooth function of phi
  const auto strength_at = [&](double friction_angle) {
    const DruckerPragerCone moved = matched_cone(parameters_.matching, strength.cohesion,
                                                 friction_angle, strength.dilatancy_angle);
    return moved.slope * pressure + moved.intercept;
  };
  const double strength_per_radian = std::abs(strength_at(strength.friction_angle + step) -
                                              strength_at(strength.friction_angle - step)) /
                                     (2.0 * step);
  const double hardening =
      std::max(strength_parameters.cohesion_hardening_modulus, 0.0) * intercept_per_cohesion +
      std::max(strength_parameters.friction_hardening_modulus, 0.0) * radians(1.0) *
          strength_per_radian;
  const double cone_modulus =
      3.0 * elastic().shear_modulus() + bulk * c.slope * c.dilatancy_slope + hardening;
  const double cone_function = von_mises_stress(stress) - c.slope * pressure - c.intercept;
  double rate = cone_modulus * slope(cone_function);
  const double cutoff = -pressure - strength.tension_limit;
  if (cutoff > 0.0) rate += bulk * slope(cutoff);
  return strength_parameters.fluidity * rate / scale;
}

}  // namespace rktsph
