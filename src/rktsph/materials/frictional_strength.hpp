// The strength shared by the frictional Perzyna materials (perzyna_drucker_prager,
// perzyna_mohr_coulomb; docs/theory.md §1.8): cohesion c, friction angle phi and dilatancy angle
// psi, linear hardening or softening of c and phi with the equivalent viscoplastic strain, the
// tension limit at the apex, and the fixed overstress scale F0 of Psi = <F/F0>^N.
//
// Angles are in degrees in the case file and in the internal variables (they are what a user
// reads back), in radians in every formula.
#pragma once

#include <functional>
#include <limits>
#include <span>

#include "rktsph/materials/parameter_reader.hpp"

namespace rktsph {

struct FrictionalParameters {
  double cohesion = 0.0;                    // c0 [Pa], >= 0
  double friction_angle = 0.0;              // phi0 [deg], in [0, kMaximumFrictionAngle]
  double dilatancy_angle = 0.0;             // psi [deg], in [0, phi0]
  double cohesion_hardening_modulus = 0.0;  // H_c [Pa]: c_rate = H_c eps_eq_rate (< 0 softening)
  double friction_hardening_modulus = 0.0;  // H_phi [deg]: phi_rate = H_phi eps_eq_rate
  double minimum_cohesion = 0.0;            // floor of c under softening [Pa], in [0, c0]
  double minimum_friction_angle = 0.0;      // floor of phi under softening [deg], in [0, phi0]
  double fluidity = 0.0;                    // gamma [1/s], > 0
  double exponent = 1.0;                    // N [-], > 0
  double reference_stress = 0.0;            // F0 [Pa], > 0
  /// Largest tensile stress [Pa] (mean stress for Drucker–Prager, each principal stress for
  /// Mohr–Coulomb); always limited to the apex c cot(phi) of the current strength.
  double tension_cutoff = std::numeric_limits<double>::infinity();
};

/// Hardening of phi stops here, so that cot(phi) and the matched cones stay finite [deg].
inline constexpr double kMaximumFrictionAngle = 89.0;

/// Reads the keys of FrictionalParameters. `default_reference` gives the default F0 from the
/// strength read so far (the material's strength measure at p = 0); F0 is required when that
/// default is 0 (c0 = 0).
FrictionalParameters read_frictional_parameters(
    ParameterReader& reader,
    const std::function<double(const FrictionalParameters&)>& default_reference);

/// The strength at a state of the internal variables, after the floors and the ceiling.
struct FrictionalStrength {
  double cohesion;         // c [Pa]
  double friction_angle;   // phi [rad]
  double dilatancy_angle;  // psi = min(psi0, phi) [rad]
  /// The largest tensile stress: min(tension_cutoff, c cot phi) [Pa] (+inf for c > 0, phi = 0).
  double tension_limit;
};

/// Internal variables shared by both materials, in this order.
struct FrictionalInternal {
  static constexpr int kEquivalentStrain = 0;  // "eps_vp" [-]
  static constexpr int kCohesion = 1;          // "cohesion" [Pa]
  static constexpr int kFrictionAngle = 2;     // "friction_angle" [deg]
  static constexpr int kCount = 3;
};

FrictionalStrength current_strength(const FrictionalParameters& parameters,
                                    std::span<const double> internal);
void initial_frictional_internal(const FrictionalParameters& parameters,
                                 std::span<double> internal);
/// Sets the rates of (eps_vp, c, phi) from the equivalent viscoplastic strain rate; c and phi
/// stop at their floors (softening) and phi at kMaximumFrictionAngle (hardening).
void frictional_internal_rates(const FrictionalParameters& parameters,
                               std::span<const double> internal, double equivalent_strain_rate,
                               std::span<double> internal_rate);
/// The apex c cot(phi) [Pa]: +inf for c > 0 at phi = 0, 0 for c = 0.
double apex_tension(double cohesion, double friction_angle_rad);
double radians(double degrees);

}  // namespace rktsph
