#include "rktsph/validation/references/terzaghi.hpp"

#include <cmath>
#include <numbers>

namespace rktsph::references {
namespace {

// Below this time factor the image (error-function) sums converge in a handful of terms and the
// Fourier series would need hundreds; above it the Fourier series needs only a few.
constexpr double kShortTimeLimit = 0.25;
// Terms below this size no longer change a double near 1.
constexpr double kNegligibleTerm = 1e-18;

/// Fourier eigenvalue M_m = π(2m + 1)/2.
double eigenvalue(int m) {
  return std::numbers::pi * (2 * m + 1) / 2.0;
}

/// ierfc(x) = ∫_x^∞ erfc(s) ds = e^{−x²}/√π − x erfc(x).
double integrated_erfc(double x) {
  return std::exp(-x * x) / std::sqrt(std::numbers::pi) - x * std::erfc(x);
}

double pressure_ratio_series(double depth_ratio, double time_factor) {
  double sum = 0.0;
  for (int m = 0;; ++m) {
    const double root = eigenvalue(m);
    const double decay = std::exp(-root * root * time_factor);
    if (decay < kNegligibleTerm) break;
    sum += 2.0 / root * std::sin(root * depth_ratio) * decay;
  }
  return sum;
}

double pressure_ratio_images(double depth_ratio, double time_factor) {
  // Odd reflection about the drained face and even reflection about the impermeable base turn the
  // column into a square wave of period 4 on the whole line; the heat kernel then gives
  //   p/p0 = 1 − Σ_m (−1)^m [erfc((2m + ζ)/(2√T)) + erfc((2m + 2 − ζ)/(2√T))].
  const double scale = 2.0 * std::sqrt(time_factor);
  double sum = 0.0;
  double sign = 1.0;
  for (int m = 0;; ++m) {
    const double term =
        std::erfc((2 * m + depth_ratio) / scale) + std::erfc((2 * m + 2 - depth_ratio) / scale);
    sum += sign * term;
    if (term < kNegligibleTerm) break;
    sign = -sign;
  }
  return 1.0 - sum;
}

double consolidation_series(double time_factor) {
  double sum = 0.0;
  for (int m = 0;; ++m) {
    const double root = eigenvalue(m);
    const double decay = std::exp(-root * root * time_factor);
    if (decay < kNegligibleTerm) break;
    sum += 2.0 / (root * root) * decay;
  }
  return 1.0 - sum;
}

double consolidation_images(double time_factor) {
  // Integrating the image form over 0 ≤ ζ ≤ 1 gives U = 2√(T/π) + 4√T Σ_{j≥1} (−1)^j ierfc(j/√T).
  const double root_time = std::sqrt(time_factor);
  double sum = 0.0;
  double sign = -1.0;
  for (int j = 1;; ++j) {
    const double term = integrated_erfc(j / root_time);
    sum += sign * term;
    if (term < kNegligibleTerm) break;
    sign = -sign;
  }
  return 2.0 * root_time / std::sqrt(std::numbers::pi) + 4.0 * root_time * sum;
}

}  // namespace

double biot_modulus(double porosity, double fluid_bulk_modulus) {
  return fluid_bulk_modulus / porosity;
}

double loading_efficiency(double oedometric_modulus, double biot_modulus) {
  return 1.0 / (1.0 + oedometric_modulus / biot_modulus);
}

double consolidation_coefficient(double hydraulic_conductivity, double fluid_unit_weight,
                                 double oedometric_modulus, double biot_modulus) {
  // Storage per unit pressure rise is the skeleton compliance 1/M plus the water's 1/Q.
  return (hydraulic_conductivity / fluid_unit_weight) /
         (1.0 / oedometric_modulus + 1.0 / biot_modulus);
}

double time_factor(double consolidation_coefficient, double time, double drainage_length) {
  return consolidation_coefficient * time / (drainage_length * drainage_length);
}

double terzaghi_pressure_ratio(double depth_ratio, double time_factor) {
  if (time_factor <= 0.0) return depth_ratio > 0.0 ? 1.0 : 0.0;
  return time_factor < kShortTimeLimit ? pressure_ratio_images(depth_ratio, time_factor)
                                       : pressure_ratio_series(depth_ratio, time_factor);
}

double terzaghi_pore_pressure(double depth, double time, double drainage_length,
                              double consolidation_coefficient, double initial_pressure) {
  return initial_pressure *
         terzaghi_pressure_ratio(depth / drainage_length,
                                 time_factor(consolidation_coefficient, time, drainage_length));
}

double degree_of_consolidation(double time_factor) {
  if (time_factor <= 0.0) return 0.0;
  return time_factor < kShortTimeLimit ? consolidation_images(time_factor)
                                       : consolidation_series(time_factor);
}

double terzaghi_settlement(double load, double drainage_length, double oedometric_modulus,
                           double biot_modulus, double time_factor) {
  const double undrained = load * drainage_length / (oedometric_modulus + biot_modulus);
  const double drained = load * drainage_length / oedometric_modulus;
  return undrained + (drained - undrained) * degree_of_consolidation(time_factor);
}

}  // namespace rktsph::references
