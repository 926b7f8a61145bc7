// Uniaxial stress (docs/theory.md §1.6): the bar carries sigma_xx; sigma_yy = sigma_zz = 0 and the
// shear stresses vanish, so its stiffness is D condensed over every other component, E.
#include "rktsph/physics/kinematics/kinematics.hpp"

namespace rktsph {

const KinematicAssumption& bar_1d() {
  static constexpr TensorComponent carried[] = {{0, 0}};
  static constexpr TensorComponent stress_free[] = {{1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
  static const KinematicAssumption kinematics(1, carried, stress_free);
  return kinematics;
}

}  // namespace rktsph
