#include "rktsph/sph/kernel.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rktsph {

namespace {

constexpr double kPi = std::numbers::pi;

/// Integral of exp(-|x|^2) / pi^(d/2) over the ball |x| < 3 in d dimensions: the share of the
/// full Gaussian's unit mass that survives the truncation at q = 3. Closed forms (radial integrals
/// of e^{-q^2} q^{d-1}): 1D erf(3); 2D 1 - e^{-9}; 3D erf(3) - (6/sqrt(pi)) e^{-9}. Dividing by it
/// makes the truncated kernel integrate to exactly 1 (docs/theory.md §4.1).
double truncated_gaussian_mass(int dimension) {
  constexpr double kCutoff = 3.0;
  const double tail = std::exp(-kCutoff * kCutoff);
  switch (dimension) {
    case 1:
      return std::erf(kCutoff);
    case 2:
      return 1.0 - tail;
    default:
      return std::erf(kCutoff) - 2.0 * kCutoff / std::sqrt(kPi) * tail;
  }
}

}  // namespace

Kernel::Kernel(KernelType type, int dimension)
    : type_(type), dimension_(dimension), normalisation_(0.0) {
  if (dimension < 1 || dimension > 3) {
    throw std::invalid_argument("Kernel: dimension must be 1, 2 or 3, got " +
                                std::to_string(dimension));
  }
  normalisation_ = normalisation_for(type, dimension);
}

double Kernel::normalisation_for(KernelType type, int dimension) {
  // Constants of docs/theory.md eq. 4.5 with the 1/h^d factored out.
  const int index = dimension - 1;
  switch (type) {
    case KernelType::CubicSpline: {
      constexpr double kCubic[3] = {2.0 / 3.0, 10.0 / (7.0 * kPi), 1.0 / kPi};
      return kCubic[index];
    }
    case KernelType::QuinticSpline: {
      // Reciprocals of the moments of f: with the integral of (a - q)^5 q^(d-1) over [0, a] equal
      // to a^(d+5) (d-1)! 5! / (d+5)!, they are 120, 478 pi / 7 and 120 pi for d = 1, 2, 3. The 3D
      // value 3/(359 pi) often quoted (and given in the brief) integrates to 360/359; it is a typo.
      constexpr double kQuintic[3] = {1.0 / 120.0, 7.0 / (478.0 * kPi), 1.0 / (120.0 * kPi)};
      return kQuintic[index];
    }
    case KernelType::Gaussian:
      return 1.0 / (std::pow(kPi, 0.5 * dimension) * truncated_gaussian_mass(dimension));
  }
  throw std::invalid_argument("Kernel: unknown kernel type");
}

KernelType kernel_type_from_name(const std::string& name) {
  if (name == "cubic_spline") return KernelType::CubicSpline;
  if (name == "quintic_spline") return KernelType::QuinticSpline;
  if (name == "gaussian") return KernelType::Gaussian;
  throw std::invalid_argument("unknown kernel '" + name +
                              "' (allowed: cubic_spline, quintic_spline, gaussian)");
}

std::string kernel_type_name(KernelType type) {
  switch (type) {
    case KernelType::CubicSpline:
      return "cubic_spline";
    case KernelType::QuinticSpline:
      return "quintic_spline";
    case KernelType::Gaussian:
      return "gaussian";
  }
  throw std::invalid_argument("kernel_type_name: unknown kernel type");
}

}  // namespace rktsph
