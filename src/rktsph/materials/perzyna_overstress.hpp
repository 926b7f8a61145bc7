// The overstress function shared by the Perzyna materials (docs/theory.md §1.3, eq. 1.5).
#pragma once

#include <cmath>

namespace rktsph {

/// <x>^N: the Macaulay bracket first (zero for x <= 0), then the power.
inline double macaulay_power(double x, double exponent) {
  if (x <= 0.0) return 0.0;
  return exponent == 1.0 ? x : std::pow(x, exponent);
}

}  // namespace rktsph
