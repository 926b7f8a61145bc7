// Plane stress in x-y (docs/theory.md §1.6): sigma_zz = sigma_yz = sigma_zx = 0; the stiffness is D
// condensed over zz, E' [[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu)/2]].
#include "rktsph/physics/kinematics/kinematics.hpp"

namespace rktsph {

const KinematicAssumption& plane_stress() {
  static constexpr TensorComponent carried[] = {{0, 0}, {1, 1}, {0, 1}};
  static constexpr TensorComponent stress_free[] = {{2, 2}, {1, 2}, {0, 2}};
  static const KinematicAssumption kinematics(2, carried, stress_free);
  return kinematics;
}

}  // namespace rktsph
