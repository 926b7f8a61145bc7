// Radial smoothing kernels W(r, h) of the SPH approximations (docs/theory.md §4.1, eq. 4.5).
//
// Kernel is a small value type: the kernel family is a switch inside inline functions, so the
// hot loops of the operators pay no virtual call and the compiler can hoist the switch.
#pragma once

#include <array>
#include <cmath>
#include <string>

#include "rktsph/sph/kernel_type.hpp"

namespace rktsph {

class Kernel {
 public:
  /// `dimension` must be 1, 2 or 3 (std::invalid_argument otherwise).
  Kernel(KernelType type, int dimension);

  KernelType type() const { return type_; }
  int dimension() const { return dimension_; }

  /// Support radius divided by h: 2 (cubic), 3 (quintic), 3 (Gaussian, truncated there).
  double support_factor() const { return type_ == KernelType::CubicSpline ? 2.0 : 3.0; }
  double support_radius(double smoothing_length) const {
    return support_factor() * smoothing_length;
  }

  /// W(r, h) [1/m^d]; zero for r >= support radius.
  double value(double distance, double smoothing_length) const {
    const double inverse_length = 1.0 / smoothing_length;
    const double q = distance * inverse_length;
    return normalisation_ * inverse_power(inverse_length) * shape(q);
  }

  /// The factors of value() and derivative() that depend on h only, for many evaluations at one
  /// smoothing length (a stencil's row): the same arithmetic, computed once.
  struct Scales {
    double inverse_length;
    double value_factor;       // normalisation / h^d
    double derivative_factor;  // normalisation / h^(d+1)
  };
  Scales scales(double smoothing_length) const {
    const double inverse_length = 1.0 / smoothing_length;
    const double value_factor = normalisation_ * inverse_power(inverse_length);
    return {inverse_length, value_factor, value_factor * inverse_length};
  }
  /// value(distance, h) and derivative(distance, h), bit for bit, with scales(h).
  double value(double distance, const Scales& at) const {
    return at.value_factor * shape(distance * at.inverse_length);
  }
  double derivative(double distance, const Scales& at) const {
    return at.derivative_factor * shape_derivative(distance * at.inverse_length);
  }

  /// dW/dr [1/m^(d+1)], never positive; 0 at r = 0 and beyond the support.
  double derivative(double distance, double smoothing_length) const {
    const double inverse_length = 1.0 / smoothing_length;
    const double q = distance * inverse_length;
    return normalisation_ * inverse_power(inverse_length) * inverse_length * shape_derivative(q);
  }

  /// Gradient with respect to x_a of W(|x_a - x_b|, h), given offset = x_a - x_b. Only the first
  /// `dimension()` components of the offset are read; the others of the result are 0.
  std::array<double, 3> gradient(const std::array<double, 3>& offset,
                                 double smoothing_length) const {
    double distance_squared = 0.0;
    for (int a = 0; a < dimension_; ++a)
      distance_squared += offset[a] * offset[a];
    return gradient(offset, std::sqrt(distance_squared), smoothing_length);
  }

  /// The same with |offset| = `distance` already known (one square root for W and its gradient).
  std::array<double, 3> gradient(const std::array<double, 3>& offset, double distance,
                                 double smoothing_length) const {
    std::array<double, 3> result{0.0, 0.0, 0.0};
    // At r = 0 the direction is undefined, but dW/dr -> 0 there, so the limit is the zero vector.
    if (distance == 0.0) return result;
    const double scale = derivative(distance, smoothing_length) / distance;
    for (int a = 0; a < dimension_; ++a)
      result[a] = scale * offset[a];
    return result;
  }

 private:
  /// 1/h^d.
  double inverse_power(double inverse_length) const {
    switch (dimension_) {
      case 1:
        return inverse_length;
      case 2:
        return inverse_length * inverse_length;
      default:
        return inverse_length * inverse_length * inverse_length;
    }
  }

  /// Dimensionless profile f(q), W = normalisation / h^d * f(r/h).
  double shape(double q) const {
    switch (type_) {
      case KernelType::CubicSpline:
        return cubic_shape(q);
      case KernelType::QuinticSpline:
        return quintic_shape(q);
      default:
        return gaussian_shape(q);
    }
  }

  /// df/dq.
  double shape_derivative(double q) const {
    switch (type_) {
      case KernelType::CubicSpline:
        return cubic_shape_derivative(q);
      case KernelType::QuinticSpline:
        return quintic_shape_derivative(q);
      default:
        return gaussian_shape_derivative(q);
    }
  }

  // Monaghan & Lattanzio (1985) cubic B-spline, support q < 2.
  static double cubic_shape(double q) {
    if (q < 1.0) return 1.0 - 1.5 * q * q + 0.75 * q * q * q;
    if (q < 2.0) {
      const double rest = 2.0 - q;
      return 0.25 * rest * rest * rest;
    }
    return 0.0;
  }
  static double cubic_shape_derivative(double q) {
    if (q < 1.0) return q * (-3.0 + 2.25 * q);
    if (q < 2.0) {
      const double rest = 2.0 - q;
      return -0.75 * rest * rest;
    }
    return 0.0;
  }

  // Morris (1997) quintic spline, support q < 3: sum of truncated powers (k - q)^5_+.
  static double fifth_power(double x) {
    const double square = x * x;
    return square * square * x;
  }
  static double fourth_power(double x) {
    const double square = x * x;
    return square * square;
  }
  static double quintic_shape(double q) {
    if (q >= 3.0) return 0.0;
    double result = fifth_power(3.0 - q);
    if (q < 2.0) result -= 6.0 * fifth_power(2.0 - q);
    if (q < 1.0) result += 15.0 * fifth_power(1.0 - q);
    return result;
  }
  static double quintic_shape_derivative(double q) {
    if (q >= 3.0) return 0.0;
    double result = -5.0 * fourth_power(3.0 - q);
    if (q < 2.0) result += 30.0 * fourth_power(2.0 - q);
    if (q < 1.0) result -= 75.0 * fourth_power(1.0 - q);
    return result;
  }

  // Gaussian truncated at q = 3 (the renormalisation is in normalisation_).
  static double gaussian_shape(double q) { return q < 3.0 ? std::exp(-q * q) : 0.0; }
  static double gaussian_shape_derivative(double q) {
    return q < 3.0 ? -2.0 * q * std::exp(-q * q) : 0.0;
  }

  /// alpha_d * h^d: the h-free part of the normalisation constant.
  static double normalisation_for(KernelType type, int dimension);

  KernelType type_;
  int dimension_;
  double normalisation_;
};

/// "cubic_spline", "quintic_spline" or "gaussian"; std::invalid_argument for anything else.
KernelType kernel_type_from_name(const std::string& name);
/// Inverse of kernel_type_from_name.
std::string kernel_type_name(KernelType type);

}  // namespace rktsph
