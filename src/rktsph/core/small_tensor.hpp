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

}  // namespace rktsph
