// Stress invariants in the Zienkiewicz–Pande set (I1, J2, theta) and the pieces of the flow vector
// m = C1 m1 + C2 m2 + C3 m3 (docs/theory.md §1.3, eqs. 1.6–1.7).
//
// All tensors are full 3D symmetric tensors in the order (xx, yy, zz, xy, yz, zx) with tensor (not
// engineering) shear components; a double contraction therefore counts each shear component twice.
// Tension is positive and p = -I1/3 is positive in compression.
#pragma once

#include "rktsph/materials/material.hpp"

namespace rktsph {

double trace(const SymmetricTensor& tensor);
/// tensor - (tr tensor / 3) I.
SymmetricTensor deviator(const SymmetricTensor& tensor);
/// a : b = a_ij b_ij.
double double_contraction(const SymmetricTensor& a, const SymmetricTensor& b);
/// The matrix product tensor · tensor (symmetric for a symmetric tensor).
SymmetricTensor square(const SymmetricTensor& tensor);
double determinant(const SymmetricTensor& tensor);
/// Isotropic Hooke's law D^e : strain = lambda tr(strain) I + 2 G strain.
SymmetricTensor apply_elastic_stiffness(const ElasticConstants& elastic,
                                        const SymmetricTensor& strain);
/// Equivalent (deviatoric) strain rate sqrt(2/3 e:e), e = dev(strain_rate) (docs/theory.md §1.3).
double equivalent_strain_rate(const SymmetricTensor& strain_rate);

/// p = -tr(stress)/3, positive in compression.
double mean_pressure(const SymmetricTensor& stress);
/// q = sqrt(3 J2) = sqrt(3/2 s:s), the Von Mises equivalent stress (equal to StressInvariants::q).
double von_mises_stress(const SymmetricTensor& stress);

struct StressInvariants {
  SymmetricTensor deviator{};  // s = stress - (I1/3) I
  double i1 = 0.0;             // tr(stress)
  double pressure = 0.0;       // p = -I1/3
  double j2 = 0.0;             // s:s / 2
  double j3 = 0.0;             // det s
  double q = 0.0;              // sqrt(3 J2)
  double sin_3theta = 0.0;     // -(3 sqrt3 / 2) J3 / J2^(3/2), clamped to [-1, 1]
  double lode_angle = 0.0;     // theta in [-pi/6, pi/6] [rad]; +pi/6 in triaxial compression
  /// False on (or round-off close to) the hydrostatic axis, where theta has no meaning; there
  /// sin_3theta = theta = 0 and the theta-dependent parts of any flow vector must be dropped.
  bool lode_defined = false;
};

/// Below this ratio sqrt(J2) / max|stress_ij| the deviator is round-off of a hydrostatic state:
/// the relative error of s is then ~1e-16 / 1e-10 = 1e-6, the most we accept in sin 3theta.
inline constexpr double kLodeDefinedRatio = 1e-10;

StressInvariants stress_invariants(const SymmetricTensor& stress);

/// Coefficients of m = C1 m1 + C2 m2 + C3 m3 (docs/theory.md eq. 1.7): C1 = dg/dI1,
/// C2 = dg/dsqrtJ2 - (tan 3theta / sqrtJ2) dg/dtheta, C3 = -sqrt3 / (2 cos 3theta) J2^(-3/2)
/// dg/dtheta.
struct FlowCoefficients {
  double c1 = 0.0;
  double c2 = 0.0;
  double c3 = 0.0;
};

/// m1 = dI1/dstress = I.
SymmetricTensor gradient_of_i1();
/// m2 = d sqrt(J2)/dstress = s / (2 sqrt J2); zero when J2 = 0 (its coefficient must then carry
/// the limit, see perzyna_modified_cam_clay.cpp).
SymmetricTensor gradient_of_sqrt_j2(const StressInvariants& invariants);
/// m3 = dJ3/dstress = s·s - (2/3) J2 I.
SymmetricTensor gradient_of_j3(const StressInvariants& invariants);
/// C1 m1 + C2 m2 + C3 m3.
SymmetricTensor flow_vector(const StressInvariants& invariants,
                            const FlowCoefficients& coefficients);

}  // namespace rktsph
