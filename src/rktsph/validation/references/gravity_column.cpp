#include "rktsph/validation/references/gravity_column.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "rktsph/validation/references/elastic_moduli.hpp"

namespace rktsph::references {
namespace {

/// Free response pieces of x'' + 2a x' + ω² x: C(t) = cos ω_d t and S(t) = sin(ω_d t)/ω_d with
/// ω_d² = ω² − a², both multiplied by e^{−at}; the hyperbolic forms cover over-damped modes.
struct DampedFree {
  double cosine;
  double sine;
};

DampedFree damped_free(double angular_frequency, double half_damping, double time) {
  const double damped_square = angular_frequency * angular_frequency - half_damping * half_damping;
  if (damped_square > 0.0) {
    const double damped = std::sqrt(damped_square);
    const double envelope = std::exp(-half_damping * time);
    return {envelope * std::cos(damped * time), envelope * std::sin(damped * time) / damped};
  }
  if (damped_square == 0.0) {
    const double envelope = std::exp(-half_damping * time);
    return {envelope, envelope * time};
  }
  // e^{−at}cosh βt and e^{−at}sinh(βt)/β from exponentials that cannot overflow (β < a).
  const double beta = std::sqrt(-damped_square);
  const double slow = std::exp((beta - half_damping) * time);
  const double fast = std::exp(-(beta + half_damping) * time);
  return {0.5 * (slow + fast), 0.5 * (slow - fast) / beta};
}

/// Response to a unit step force from rest: (1 − e^{−at}(C + a S))/ω².
double step_response(double angular_frequency, double half_damping, double time) {
  if (time <= 0.0) return 0.0;
  const DampedFree free = damped_free(angular_frequency, half_damping, time);
  return (1.0 - free.cosine - half_damping * free.sine) / (angular_frequency * angular_frequency);
}

/// Response to a unit ramp force F = t from rest (the integral of the step response):
/// [t − 2a/ω² + e^{−at}((2a/ω²) C + ((2a² − ω²)/ω²) S)]/ω².
double ramp_response(double angular_frequency, double half_damping, double time) {
  if (time <= 0.0) return 0.0;
  const double w2 = angular_frequency * angular_frequency;
  const DampedFree free = damped_free(angular_frequency, half_damping, time);
  return (time - 2.0 * half_damping / w2 + (2.0 * half_damping / w2) * free.cosine +
          ((2.0 * half_damping * half_damping - w2) / w2) * free.sine) /
         w2;
}

/// Modal coordinate per unit modal force g·Γ_n, for the ramp f(t) = min(t/t_r, 1).
double modal_response(double angular_frequency, double half_damping, double ramp_duration,
                      double time) {
  if (ramp_duration <= 0.0) return step_response(angular_frequency, half_damping, time);
  // min(t/t_r, 1) = [t − (t − t_r)⁺]/t_r, so the response is a difference of two ramps.
  return (ramp_response(angular_frequency, half_damping, time) -
          ramp_response(angular_frequency, half_damping, time - ramp_duration)) /
         ramp_duration;
}

double gravity_factor(double ramp_duration, double time) {
  if (time <= 0.0) return 0.0;
  return ramp_duration <= 0.0 ? 1.0 : std::min(time / ramp_duration, 1.0);
}

}  // namespace

double geostatic_vertical_stress(double density, double gravity, double depth) {
  return -density * gravity * depth;
}

double geostatic_horizontal_stress(double density, double gravity, double depth,
                                   double poisson_ratio) {
  return earth_pressure_at_rest(poisson_ratio) * geostatic_vertical_stress(density, gravity, depth);
}

double gravity_column_wave_speed(const GravityColumn& column) {
  return std::sqrt(oedometric_modulus(column.young_modulus, column.poisson_ratio) / column.density);
}

double gravity_column_fundamental_period(const GravityColumn& column) {
  return 4.0 * column.height / gravity_column_wave_speed(column);
}

double ramp_oscillation_amplitude(double angular_frequency, double ramp_duration) {
  if (ramp_duration <= 0.0) return 1.0;
  const double half_phase = 0.5 * angular_frequency * ramp_duration;
  return std::abs(std::sin(half_phase)) / half_phase;
}

double gravity_column_vertical_stress(const GravityColumn& column, double depth, double time,
                                      int modes, bool static_correction) {
  if (!(column.height > 0.0) || !(column.density > 0.0) || !(column.young_modulus > 0.0) ||
      modes < 1) {
    throw std::invalid_argument("gravity column: height, density, E > 0 and modes ≥ 1");
  }
  const double modulus = oedometric_modulus(column.young_modulus, column.poisson_ratio);
  const double speed = std::sqrt(modulus / column.density);
  const double half_damping = 0.5 * column.mass_damping;
  const double factor = gravity_factor(column.ramp_duration, time);
  double sum = 0.0;
  for (int n = 1; n <= modes; ++n) {
    const double wavenumber = (2 * n - 1) * std::numbers::pi / (2.0 * column.height);
    const double angular_frequency = speed * wavenumber;
    const double participation = (n % 2 == 1 ? 2.0 : -2.0) / (wavenumber * column.height);
    double coordinate = modal_response(angular_frequency, half_damping, column.ramp_duration, time);
    // The quasi-static coordinate f(t)/ω_n² sums (over all modes) to the exact −ρ g z f(t).
    if (static_correction) coordinate -= factor / (angular_frequency * angular_frequency);
    sum += column.gravity * participation * coordinate * wavenumber * std::sin(wavenumber * depth);
  }
  const double dynamic = -modulus * sum;
  return static_correction
             ? geostatic_vertical_stress(column.density, column.gravity, depth) * factor + dynamic
             : dynamic;
}

}  // namespace rktsph::references
