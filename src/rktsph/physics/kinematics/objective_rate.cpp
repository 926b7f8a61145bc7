#include "rktsph/physics/kinematics/objective_rate.hpp"

namespace rktsph {

PlaneRotation hughes_winget_rotation(double spin_xy, double interval) {
  // W = w J with J = [[0, 1], [-1, 0]] and J^2 = -I, so (I - aJ)^-1 = (I + aJ) / (1 + a^2) and
  // Q = (I + aJ)^2 / (1 + a^2) = ((1 - a^2) I + 2a J) / (1 + a^2), a = w dt / 2 (eq. 9.2).
  const double a = 0.5 * spin_xy * interval;
  const double inverse = 1.0 / (1.0 + a * a);
  return {(1.0 - a * a) * inverse, 2.0 * a * inverse};
}

void rotate_plane_stress(const PlaneRotation& q, double& xx, double& yy, double& xy) {
  // (Q sigma Q^T) with Q = [[c, s], [-s, c]].
  const double c = q.c, s = q.s;
  const double cc = c * c, ss = s * s, cs = c * s;
  const double new_xx = cc * xx + 2.0 * cs * xy + ss * yy;
  const double new_yy = ss * xx - 2.0 * cs * xy + cc * yy;
  const double new_xy = cs * (yy - xx) + (cc - ss) * xy;
  xx = new_xx;
  yy = new_yy;
  xy = new_xy;
}

}  // namespace rktsph
