// Closed forms of Mohr–Coulomb soil mechanics for the frictional material tests, and the strain
// paths that reach them. Nothing here calls the code under test: the strengths are the classical
// ones in principal stresses (compression positive here, as soil mechanics writes them).
#pragma once

#include <cmath>
#include <numbers>

#include "rktsph/materials/point_driver.hpp"

namespace rktsph::test_support {

inline double to_radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

/// Passive coefficient Kp = (1 + sin phi) / (1 - sin phi) = tan^2(45° + phi/2).
inline double passive_coefficient(double friction_degrees) {
  const double s = std::sin(to_radians(friction_degrees));
  return (1.0 + s) / (1.0 - s);
}

/// Mohr–Coulomb major principal stress at failure for a minor one (both compression positive):
/// sigma1 = sigma3 Kp + 2 c sqrt(Kp).
inline double major_at_failure(double minor, double cohesion, double friction_degrees) {
  const double kp = passive_coefficient(friction_degrees);
  return minor * kp + 2.0 * cohesion * std::sqrt(kp);
}

/// The minor principal stress at failure for a major one: the inverse of major_at_failure.
inline double minor_at_failure(double major, double cohesion, double friction_degrees) {
  const double kp = passive_coefficient(friction_degrees);
  return (major - 2.0 * cohesion * std::sqrt(kp)) / kp;
}

/// Steady shear stress of plane-strain simple shear under a constant normal stress sigma_n
/// (compression positive) for Mohr–Coulomb with coaxial non-associated flow (Davis 1968):
/// tau = (sigma_n sin phi + c cos phi) cos psi / (1 - sin phi sin psi).
inline double simple_shear_strength(double normal_stress, double cohesion, double friction_degrees,
                                    double dilatancy_degrees) {
  const double sin_phi = std::sin(to_radians(friction_degrees));
  const double sin_psi = std::sin(to_radians(dilatancy_degrees));
  return (normal_stress * sin_phi + cohesion * std::cos(to_radians(friction_degrees))) *
         std::cos(to_radians(dilatancy_degrees)) / (1.0 - sin_phi * sin_psi);
}

/// Triaxial dilatancy of Mohr–Coulomb flow at the compression corner: eps_v_rate / eps_axial_rate
/// = -2 sin psi / (1 - sin psi) (tension-positive strains, axial shortening).
inline double triaxial_compression_dilatancy(double dilatancy_degrees) {
  const double s = std::sin(to_radians(dilatancy_degrees));
  return -2.0 * s / (1.0 - s);
}

/// Triaxial extension corner: eps_v_rate / eps_axial_rate = 2 sin psi / (1 + sin psi) with the
/// axial strain lengthening (axial stress the minor compression).
inline double triaxial_extension_dilatancy(double dilatancy_degrees) {
  const double s = std::sin(to_radians(dilatancy_degrees));
  return 2.0 * s / (1.0 + s);
}

/// Plane-strain simple shear at a constant normal (yy) stress: eps_xx = eps_zz = 0, engineering
/// shear rate `shear_rate` in xy, sigma_yy held; the other shears held at zero strain.
inline StrainPath simple_shear(double shear_rate, double duration) {
  StrainPath path;
  path.control[1] = PathControl::Stress;
  path.rate = [shear_rate](double) {
    return SymmetricTensor{0.0, 0.0, 0.0, 0.5 * shear_rate, 0.0, 0.0};
  };
  path.duration = duration;
  return path;
}

}  // namespace rktsph::test_support
