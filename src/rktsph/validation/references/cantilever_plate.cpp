#include "rktsph/validation/references/cantilever_plate.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "rktsph/validation/references/elastic_moduli.hpp"

namespace rktsph::references {
namespace {

// g(x) = 1 + cos x cosh x, whose roots are the clamped-free wave numbers k_n L.
double frequency_function(double x) {
  return 1.0 + std::cos(x) * std::cosh(x);
}

void require_plate(const CantileverPlate& plate) {
  if (!(plate.length > 0.0) || !(plate.thickness > 0.0) || !(plate.young_modulus > 0.0) ||
      !(plate.density > 0.0))
    throw std::invalid_argument(
        "cantilever plate: length, thickness, modulus, density must be > 0");
  if (!(plate.poisson_ratio > -1.0 && plate.poisson_ratio < 0.5))
    throw std::invalid_argument("cantilever plate: Poisson's ratio must be in (-1, 0.5)");
}

}  // namespace

double cantilever_mode_root(int n) {
  if (n < 1) throw std::invalid_argument("cantilever_mode_root: n must be >= 1");
  // cos x cosh x = -1 needs |cos x| <= 1/cosh x: one root in each [(n - 1)π, nπ], where g changes
  // sign once (g(0) = 2, g(π) < 0, and g alternates in sign at the multiples of π beyond). Sixty
  // halvings of π reach round-off.
  constexpr double kPi = std::numbers::pi;
  double low = (n - 1) * kPi, high = n * kPi;
  const bool positive_at_low = frequency_function(low) > 0.0;
  for (int i = 0; i < 60; ++i) {
    const double middle = 0.5 * (low + high);
    if ((frequency_function(middle) > 0.0) == positive_at_low)
      low = middle;
    else
      high = middle;
  }
  return 0.5 * (low + high);
}

double cantilever_plate_angular_frequency(const CantileverPlate& plate) {
  require_plate(plate);
  const double k = cantilever_mode_root(1) / plate.length;
  const double plate_modulus =
      plate.young_modulus / (1.0 - plate.poisson_ratio * plate.poisson_ratio);
  return k * k * plate.thickness * std::sqrt(plate_modulus / (12.0 * plate.density));
}

double cantilever_plate_period(const CantileverPlate& plate) {
  return 2.0 * std::numbers::pi / cantilever_plate_angular_frequency(plate);
}

double cantilever_plate_velocity_scale(const CantileverPlate& plate) {
  require_plate(plate);
  return std::sqrt(bulk_modulus(plate.young_modulus, plate.poisson_ratio) / plate.density);
}

}  // namespace rktsph::references
