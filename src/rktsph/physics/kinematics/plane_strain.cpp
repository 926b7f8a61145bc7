// Plane strain in x-y (docs/theory.md §1.6): eps_zz = eps_yz = eps_zx = 0. sigma_zz is carried
// because the invariants need it (docs/theory.md §7.4); the stiffness is D restricted to xx,
// yy, xy, zz.
#include "rktsph/physics/kinematics/kinematics.hpp"

namespace rktsph {

const KinematicAssumption& plane_strain() {
  static constexpr TensorComponent carried[] = {{0, 0}, {1, 1}, {0, 1}, {2, 2}};
  static const KinematicAssumption kinematics(2, carried, {});
  return kinematics;
}

}  // namespace rktsph
