#include "rktsph/materials/frictional_strength.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rktsph {

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

double apex_tension(double cohesion, double friction_angle_rad) {
  if (cohesion <= 0.0) return 0.0;
  const double tangent = std::tan(friction_angle_rad);
  return tangent > 0.0 ? cohesion / tangent : std::numeric_limits<double>::infinity();
}

FrictionalParameters read_frictional_parameters(
    ParameterReader& reader,
    const std::function<double(const FrictionalParameters&)>& default_reference) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  FrictionalParameters p;
  p.cohesion = reader.required("cohesion", 0.0, infinity);
  // A soil with neither cohesion nor friction has no strength at all: phi > 0 when c = 0.
  p.friction_angle =
      reader.required("friction_angle", 0.0, kMaximumFrictionAngle, p.cohesion == 0.0);
  // psi <= phi: on a Mohr–Coulomb plane the plastic dissipation sigma : eps_vp_rate per unit
  // rate is c cos(phi) - (sigma1 + sigma3)/2 (sin(phi) - sin(psi)) in compression-negative
  // stresses, negative at high pressure if psi > phi (docs/theory.md §1.8).
  p.dilatancy_angle = reader.optional("dilatancy_angle", 0.0, 0.0, p.friction_angle);
  p.cohesion_hardening_modulus =
      reader.optional("cohesion_hardening_modulus", 0.0, -infinity, infinity);
  p.friction_hardening_modulus =
      reader.optional("friction_hardening_modulus", 0.0, -infinity, infinity);
  // F0 is fixed (below), so c and phi may soften to 0 without a singular Psi.
  p.minimum_cohesion = reader.optional("minimum_cohesion", 0.0, 0.0, p.cohesion);
  p.minimum_friction_angle = reader.optional("minimum_friction_angle", 0.0, 0.0, p.friction_angle);
  p.fluidity = reader.required("fluidity", 0.0, infinity, true);
  p.exponent = reader.optional("exponent", 1.0, 0.0, infinity, true);
  // Psi = <F/F0>^N needs a stress scale; the strength at p = 0 is the natural one, and a
  // cohesionless soil has none, so there the user gives it.
  const double fallback = default_reference(p);
  p.reference_stress = fallback > 0.0
                           ? reader.optional("reference_stress", fallback, 0.0, infinity, true)
                           : reader.required("reference_stress", 0.0, infinity, true);
  // Off unless given: the apex c cot(phi) is always a limit (docs/theory.md §1.8).
  p.tension_cutoff = reader.optional("tension_cutoff", infinity, 0.0, infinity);
  return p;
}

void initial_frictional_internal(const FrictionalParameters& parameters,
                                 std::span<double> internal) {
  internal[FrictionalInternal::kEquivalentStrain] = 0.0;
  internal[FrictionalInternal::kCohesion] = parameters.cohesion;
  internal[FrictionalInternal::kFrictionAngle] = parameters.friction_angle;
}

FrictionalStrength current_strength(const FrictionalParameters& parameters,
                                    std::span<const double> internal) {
  FrictionalStrength strength;
  strength.cohesion =
      std::max(internal[FrictionalInternal::kCohesion], parameters.minimum_cohesion);
  const double friction_degrees =
      std::clamp(internal[FrictionalInternal::kFrictionAngle], parameters.minimum_friction_angle,
                 kMaximumFrictionAngle);
  strength.friction_angle = radians(friction_degrees);
  strength.dilatancy_angle = radians(std::min(parameters.dilatancy_angle, friction_degrees));
  strength.tension_limit =
      std::min(parameters.tension_cutoff, apex_tension(strength.cohesion, strength.friction_angle));
  return strength;
}

void frictional_internal_rates(const FrictionalParameters& parameters,
                               std::span<const double> internal, double equivalent_strain_rate,
                               std::span<double> internal_rate) {
  internal_rate[FrictionalInternal::kEquivalentStrain] = equivalent_strain_rate;
  const double cohesion = internal[FrictionalInternal::kCohesion];
  const double friction = internal[FrictionalInternal::kFrictionAngle];
  const double cohesion_modulus = parameters.cohesion_hardening_modulus;
  const double friction_modulus = parameters.friction_hardening_modulus;
  // As for the yield stress of perzyna_von_mises: the rate stops once the floor is reached.
  const bool cohesion_stops = cohesion_modulus < 0.0 && cohesion <= parameters.minimum_cohesion;
  const bool friction_stops =
      (friction_modulus < 0.0 && friction <= parameters.minimum_friction_angle) ||
      (friction_modulus > 0.0 && friction >= kMaximumFrictionAngle);
  internal_rate[FrictionalInternal::kCohesion] =
      cohesion_stops ? 0.0 : cohesion_modulus * equivalent_strain_rate;
  internal_rate[FrictionalInternal::kFrictionAngle] =
      friction_stops ? 0.0 : friction_modulus * equivalent_strain_rate;
}

}  // namespace rktsph
