// The small-tensor vocabulary of the code: one 3-vector and one symmetric tensor, whatever the
// dimension of the case (unused components are zero), so that 1D, 2D and 3D share one form.
#pragma once

#include <array>

namespace rktsph {

/// A point, a displacement or a unit normal: components x, y, z [m or -].
using Vec3 = std::array<double, 3>;

/// A symmetric second-order tensor (stress, strain, their rates) in Voigt order
/// xx, yy, zz, xy, yz, zx, with tensor (not engineering) shear components.
using SymmetricTensor = std::array<double, 6>;

/// True if unit vectors a and b point the same way (to within rounding).
inline bool same_direction(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] > 1.0 - 1e-9;
}

}  // namespace rktsph
