#include "rktsph/physics/field_layout.hpp"

namespace rktsph {

FieldLayout::FieldLayout(const KinematicAssumption& kinematics, bool pore_pressure)
    : kinematics_(&kinematics) {
  static const char* const velocity_names[] = {"velocity_x", "velocity_y", "velocity_z"};
  for (int a = 0; a < dimension(); ++a) {
    names_.emplace_back(velocity_names[a]);
    parities_.push_back(vector_parity(a));
  }
  for (int c = 0; c < stress_count(); ++c) {
    const TensorComponent component = kinematics.stress_component(c);
    names_.push_back(kinematics.stress_name(c));
    parities_.push_back(tensor_parity(component.i, component.j));
  }
  if (pore_pressure) {
    pore_pressure_ = field_count();
    names_.emplace_back("pore_pressure");
    parities_.push_back(kEven);  // a scalar: even under every reflection
  }
}

int FieldLayout::stress(int i, int j) const {
  const int c = kinematics_->carried_index(i, j);
  return c < 0 ? -1 : stress_component(c);
}

}  // namespace rktsph
