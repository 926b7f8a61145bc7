#include "rktsph/validation/references/harmonic_column.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "rktsph/core/error.hpp"
#include "rktsph/validation/references/elastic_moduli.hpp"

namespace rktsph::references {
namespace {

using Complex = std::complex<double>;
constexpr Complex kI{0.0, 1.0};

bool positive_finite(double value) {
  return value > 0.0 && std::isfinite(value);
}

void validate(const HarmonicColumn& c) {
  if (!positive_finite(c.depth) || !positive_finite(c.constrained_modulus) ||
      !positive_finite(c.biot_modulus) || !positive_finite(c.mixture_density) ||
      !positive_finite(c.permeability) || !positive_finite(c.angular_frequency) ||
      !(c.fluid_density >= 0.0) || !(c.biot_coefficient > 0.0)) {
    // Q = ∞ makes s = 0 a root and two of the four exponentials coincide; k̄ = 0 is the
    // undrained limit, which has its own function.
    throw std::invalid_argument(
        "HarmonicColumn: depth, D, Q, ρ, k̄ and ω must be positive and finite, ρ_f ≥ 0, α > 0");
  }
}

/// Solves the 4×4 system by Gaussian elimination with row equilibration and partial pivoting.
std::array<Complex, 4> solve4(std::array<std::array<Complex, 4>, 4> matrix,
                              std::array<Complex, 4> rhs) {
  // Rows mix units (Pa, m, Pa/m), so each is scaled to a largest entry of 1 before pivoting.
  for (int row = 0; row < 4; ++row) {
    double largest = 0.0;
    for (const Complex& entry : matrix[row])
      largest = std::max(largest, std::abs(entry));
    if (largest == 0.0) throw RunError("harmonic column: singular boundary system");
    for (Complex& entry : matrix[row])
      entry /= largest;
    rhs[row] /= largest;
  }
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    for (int row = col + 1; row < 4; ++row) {
      if (std::abs(matrix[row][col]) > std::abs(matrix[pivot][col])) pivot = row;
    }
    if (std::abs(matrix[pivot][col]) < 1e-300) {
      throw RunError("harmonic column: singular boundary system");
    }
    std::swap(matrix[col], matrix[pivot]);
    std::swap(rhs[col], rhs[pivot]);
    for (int row = col + 1; row < 4; ++row) {
      const Complex factor = matrix[row][col] / matrix[col][col];
      for (int k = col; k < 4; ++k)
        matrix[row][k] -= factor * matrix[col][k];
      rhs[row] -= factor * rhs[col];
    }
  }
  std::array<Complex, 4> solution{};
  for (int row = 3; row >= 0; --row) {
    Complex sum = rhs[row];
    for (int k = row + 1; k < 4; ++k)
      sum -= matrix[row][k] * solution[k];
    solution[row] = sum / matrix[row][row];
  }
  return solution;
}

/// Roots s of A2 s² + A1 s + A0 = 0 without cancellation (one root may be very large when k̄ is
/// small: that is the drained boundary layer).
std::array<Complex, 2> quadratic_roots(Complex a2, Complex a1, Complex a0) {
  const Complex discriminant = std::sqrt(a1 * a1 - 4.0 * a2 * a0);
  const Complex plus = a1 + discriminant;
  const Complex minus = a1 - discriminant;
  const Complex q = -0.5 * (std::abs(plus) >= std::abs(minus) ? plus : minus);
  return {q / a2, a0 / q};
}

}  // namespace

HarmonicColumn HarmonicColumn::dimensionless(double permeability_group, double frequency_group,
                                             double fluid_density_ratio, double modulus_ratio) {
  HarmonicColumn column;
  column.depth = 1.0;
  column.mixture_density = 1.0;
  column.biot_coefficient = 1.0;
  // V_c² = (D + Q)/ρ = 1 with D = (D/Q)·Q.
  column.biot_modulus = 1.0 / (1.0 + modulus_ratio);
  column.constrained_modulus = modulus_ratio * column.biot_modulus;
  column.fluid_density = fluid_density_ratio;
  column.angular_frequency = std::sqrt(frequency_group);
  column.permeability = permeability_group * column.angular_frequency;
  return column;
}

HarmonicColumn HarmonicColumn::physical(double depth, double young_modulus, double poisson_ratio,
                                        double porosity, double solid_density, double fluid_density,
                                        double fluid_bulk_modulus, double hydraulic_conductivity,
                                        double period, double gravity, double load) {
  HarmonicColumn column;
  column.depth = depth;
  column.constrained_modulus = oedometric_modulus(young_modulus, poisson_ratio);
  column.biot_modulus = fluid_bulk_modulus / porosity;
  column.biot_coefficient = 1.0;
  column.mixture_density = (1.0 - porosity) * solid_density + porosity * fluid_density;
  column.fluid_density = fluid_density;
  column.permeability = hydraulic_conductivity / (fluid_density * gravity);
  column.angular_frequency = 2.0 * std::numbers::pi / period;
  column.load_amplitude = load;
  return column;
}

double undrained_wave_speed(const HarmonicColumn& c) {
  return std::sqrt(
      (c.constrained_modulus + c.biot_coefficient * c.biot_coefficient * c.biot_modulus) /
      c.mixture_density);
}

double undrained_static_pressure(const HarmonicColumn& c) {
  return c.biot_coefficient * c.biot_modulus * c.load_amplitude /
         (c.constrained_modulus + c.biot_coefficient * c.biot_coefficient * c.biot_modulus);
}

double permeability_group(const HarmonicColumn& c) {
  const double speed = undrained_wave_speed(c);
  return c.permeability * c.mixture_density * speed * speed /
         (c.angular_frequency * c.depth * c.depth);
}

double frequency_group(const HarmonicColumn& c) {
  const double ratio = c.angular_frequency * c.depth / undrained_wave_speed(c);
  return ratio * ratio;
}

HarmonicColumnSolution::HarmonicColumnSolution(const HarmonicColumn& column) : column_(column) {
  validate(column_);
  const double d = column_.constrained_modulus;
  const double q = column_.biot_modulus;
  const double alpha = column_.biot_coefficient;
  const double rho = column_.mixture_density;
  const double kbar = column_.permeability;
  const double omega = column_.angular_frequency;
  const double inertia = rho * omega * omega;
  // Fluid inertia in Darcy's law, as a coupling of the storage equation to U′.
  const Complex coupling =
      kI * omega * alpha +
      (column_.fluid_acceleration_in_darcy ? kbar * column_.fluid_density * omega * omega : 0.0);

  // det [[D s + ρω², −αμ], [μ·coupling, iω/Q − k̄ s]] = 0 with μ² = s.
  const Complex a2 = -d * kbar;
  const Complex a1 = kI * omega * d / q - inertia * kbar + alpha * coupling;
  const Complex a0 = kI * omega * inertia / q;
  const std::array<Complex, 2> roots = quadratic_roots(a2, a1, a0);

  for (int root = 0; root < 2; ++root) {
    const Complex s = roots[root];
    const Complex lambda = std::sqrt(s);  // principal root: Re λ ≥ 0
    const Complex momentum_diagonal = d * s + inertia;
    const Complex storage_diagonal = kI * omega / q - kbar * s;
    // Take the null vector from the equation whose diagonal suffers less cancellation.
    const double momentum_quality = std::abs(momentum_diagonal) / (std::abs(d * s) + inertia);
    const double storage_quality = std::abs(storage_diagonal) / (omega / q + kbar * std::abs(s));
    for (int side = 0; side < 2; ++side) {
      Mode& mode = modes_[2 * root + side];
      mode.exponent = side == 0 ? -lambda : lambda;
      mode.origin = side == 0 ? 0.0 : column_.depth;
      if (momentum_quality >= storage_quality) {
        mode.displacement = alpha * mode.exponent;
        mode.pressure = momentum_diagonal;
      } else {
        mode.displacement = storage_diagonal;
        mode.pressure = -mode.exponent * coupling;
      }
    }
  }

  std::array<std::array<Complex, 4>, 4> matrix{};
  for (int j = 0; j < 4; ++j) {
    const Mode& mode = modes_[j];
    const Complex at_top = std::exp(mode.exponent * (0.0 - mode.origin));
    const Complex at_base = std::exp(mode.exponent * (column_.depth - mode.origin));
    matrix[0][j] = (d * mode.exponent * mode.displacement - alpha * mode.pressure) * at_top;
    matrix[1][j] = mode.pressure * at_top;
    matrix[2][j] = mode.displacement * at_base;
    matrix[3][j] = mode.exponent * mode.pressure * at_base;
  }
  const std::array<Complex, 4> weights =
      solve4(matrix, {Complex(-column_.load_amplitude), 0.0, 0.0, 0.0});
  for (int j = 0; j < 4; ++j) {
    modes_[j].displacement *= weights[j];
    modes_[j].pressure *= weights[j];
  }
}

std::complex<double> HarmonicColumnSolution::pressure(double z) const {
  Complex sum = 0.0;
  for (const Mode& mode : modes_)
    sum += mode.pressure * std::exp(mode.exponent * (z - mode.origin));
  return sum;
}

std::complex<double> HarmonicColumnSolution::displacement(double z) const {
  Complex sum = 0.0;
  for (const Mode& mode : modes_) {
    sum += mode.displacement * std::exp(mode.exponent * (z - mode.origin));
  }
  return sum;
}

double HarmonicColumnSolution::pressure_ratio(double z) const {
  return std::abs(pressure(z)) / column_.load_amplitude;
}

double HarmonicColumnSolution::pressure_phase(double z) const {
  return std::arg(pressure(z));
}

std::complex<double> undrained_harmonic_pressure(const HarmonicColumn& column, double z) {
  const double wavenumber = column.angular_frequency / undrained_wave_speed(column);
  return undrained_static_pressure(column) * std::cos(wavenumber * (column.depth - z)) /
         std::cos(wavenumber * column.depth);
}

std::complex<double> quasi_static_harmonic_pressure(const HarmonicColumn& column, double z) {
  const double alpha = column.biot_coefficient;
  const Complex kappa =
      std::sqrt(kI * column.angular_frequency *
                (alpha * alpha / column.constrained_modulus + 1.0 / column.biot_modulus) /
                column.permeability);
  // cosh κ(L−z)/cosh κL written with decaying exponentials only (Re κ > 0), so a thin boundary
  // layer (large κL) cannot overflow.
  const double depth = column.depth;
  const Complex ratio = (std::exp(-kappa * z) + std::exp(-kappa * (2.0 * depth - z))) /
                        (1.0 + std::exp(-2.0 * kappa * depth));
  return undrained_static_pressure(column) * (1.0 - ratio);
}

}  // namespace rktsph::references
