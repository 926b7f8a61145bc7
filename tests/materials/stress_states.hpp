// Test helpers for the material tests: stress states built from principal values and a rotation,
// invariants computed independently from the eigenvalues (Eigen), and central finite differences
// of a scalar function of stress. Nothing here calls the code under test.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "rktsph/materials/material.hpp"

namespace rktsph::test_support {

inline Eigen::Matrix3d to_matrix(const SymmetricTensor& t) {
  Eigen::Matrix3d m;
  m << t[0], t[3], t[5],  //
      t[3], t[1], t[4],   //
      t[5], t[4], t[2];
  return m;
}

inline SymmetricTensor to_tensor(const Eigen::Matrix3d& m) {
  return {m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(1, 2), m(2, 0)};
}

/// A rotation drawn from a seeded generator (normalised Gaussian quaternion: uniform on SO(3)).
inline Eigen::Matrix3d random_rotation(std::mt19937& generator) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Quaterniond quaternion(normal(generator), normal(generator), normal(generator),
                                normal(generator));
  quaternion.normalize();
  return quaternion.toRotationMatrix();
}

inline SymmetricTensor rotated_principal(const std::array<double, 3>& principal,
                                         const Eigen::Matrix3d& rotation) {
  const Eigen::Vector3d values(principal[0], principal[1], principal[2]);
  return to_tensor(rotation * values.asDiagonal() * rotation.transpose());
}

/// Principal stresses with pressure p, deviatoric measure q and Lode angle theta in the
/// Zienkiewicz–Pande parametrisation (s_k = (2q/3) sin(theta + 2pi/3), (2q/3) sin(theta),
/// (2q/3) sin(theta - 2pi/3)); at theta = +pi/6 the third one is the most compressive.
inline std::array<double, 3> principal_from_invariants(double pressure, double q, double theta) {
  const double radius = 2.0 * q / 3.0;
  const double third = 2.0 * std::numbers::pi / 3.0;
  return {-pressure + radius * std::sin(theta + third), -pressure + radius * std::sin(theta),
          -pressure + radius * std::sin(theta - third)};
}

/// Invariants from the eigenvalues of the stress matrix.
struct PrincipalInvariants {
  double pressure, j2, j3, q, sin_3theta;
};

inline PrincipalInvariants principal_invariants(const SymmetricTensor& stress) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(to_matrix(stress),
                                                              Eigen::EigenvaluesOnly);
  const Eigen::Vector3d values = solver.eigenvalues();
  const double mean = values.sum() / 3.0;
  const Eigen::Vector3d deviatoric = values.array() - mean;
  PrincipalInvariants result;
  result.pressure = -mean;
  result.j2 = 0.5 * deviatoric.squaredNorm();
  result.j3 = deviatoric.prod();
  result.q = std::sqrt(3.0 * result.j2);
  result.sin_3theta = -1.5 * std::sqrt(3.0) * result.j3 / std::pow(result.j2, 1.5);
  return result;
}

/// Central-difference gradient dg/dstress in tensor components. Moving the stored shear entry
/// moves both sigma_ij and sigma_ji, so its difference quotient is twice the tensor component.
inline SymmetricTensor finite_difference_gradient(
    const std::function<double(const SymmetricTensor&)>& function, const SymmetricTensor& stress,
    double step) {
  SymmetricTensor gradient;
  for (int i = 0; i < 6; ++i) {
    SymmetricTensor plus = stress, minus = stress;
    plus[i] += step;
    minus[i] -= step;
    const double quotient = (function(plus) - function(minus)) / (2.0 * step);
    gradient[i] = i < 3 ? quotient : 0.5 * quotient;
  }
  return gradient;
}

/// Least-squares coefficients (C1, C2, C3) of `gradient` on m1 = I, m2 = s/(2 sqrtJ2) and
/// m3 = s s - (2/3) J2 I, all built here from the matrix of `stress` (docs/theory.md eq. 1.7).
inline std::array<double, 3> project_on_invariant_gradients(const SymmetricTensor& gradient,
                                                            const SymmetricTensor& stress) {
  const Eigen::Matrix3d matrix = to_matrix(stress);
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d s = matrix - matrix.trace() / 3.0 * identity;
  const double j2 = 0.5 * (s.array() * s.array()).sum();
  const std::array<Eigen::Matrix3d, 3> basis = {identity, s / (2.0 * std::sqrt(j2)),
                                                s * s - 2.0 / 3.0 * j2 * identity};
  const Eigen::Matrix3d target = to_matrix(gradient);
  Eigen::Matrix3d gram;
  Eigen::Vector3d right;
  for (int a = 0; a < 3; ++a) {
    right[a] = (basis[a].array() * target.array()).sum();
    for (int b = 0; b < 3; ++b)
      gram(a, b) = (basis[a].array() * basis[b].array()).sum();
  }
  const Eigen::Vector3d c = gram.ldlt().solve(right);
  return {c[0], c[1], c[2]};
}

/// Tensor norm sqrt(a:a).
inline double tensor_norm(const SymmetricTensor& t) {
  return std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2] +
                   2.0 * (t[3] * t[3] + t[4] * t[4] + t[5] * t[5]));
}

inline double distance(const SymmetricTensor& a, const SymmetricTensor& b) {
  SymmetricTensor difference;
  for (int i = 0; i < 6; ++i)
    difference[i] = a[i] - b[i];
  return tensor_norm(difference);
}

}  // namespace rktsph::test_support
