// The corotational part of the Jaumann stress rate as an incremental rotation (docs/theory.md
// §9.2, eq. 9.2): sigma <- Q sigma Q^T with the Hughes–Winget rotation
// Q = (I - dt W / 2)^-1 (I + dt W / 2), W = skw(grad v). Q is exactly orthogonal, so a rigid
// rotation leaves the stress invariants unchanged however large the step.
#pragma once

#include <array>

namespace rktsph {

/// The in-plane (xy) rotation Q = [[c, s], [-s, c]] of the spin W_xy = (dv_x/dy - dv_y/dx)/2 over
/// `interval`.
struct PlaneRotation {
  double c = 1.0;
  double s = 0.0;
};

PlaneRotation hughes_winget_rotation(double spin_xy, double interval);

/// Rotates the in-plane stress (xx, yy, xy) by Q: sigma <- Q sigma Q^T. sigma_zz is unchanged.
void rotate_plane_stress(const PlaneRotation& q, double& xx, double& yy, double& xy);

}  // namespace rktsph
