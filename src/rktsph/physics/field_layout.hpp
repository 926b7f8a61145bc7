// Where each unknown of a solid model sits among the fields (docs/theory.md §1.2, §6.1): the
// velocity components, then the carried stress components of the kinematic setting, then the pore
// pressure of the saturated model. The gradient of field f along axis a is gradient field
// f * dimension + a (the PhysicsModel::flux_rate contract). Names and parities exist only here.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "rktsph/physics/kinematics/kinematics.hpp"
#include "rktsph/sph/operators.hpp"

namespace rktsph {

class FieldLayout {
 public:
  FieldLayout(const KinematicAssumption& kinematics, bool pore_pressure);

  const KinematicAssumption& kinematics() const { return *kinematics_; }
  int dimension() const { return kinematics_->dimension(); }
  int field_count() const { return static_cast<int>(names_.size()); }
  const std::vector<std::string>& names() const { return names_; }
  std::span<const Parity> parities() const { return parities_; }

  /// Field of velocity component `axis`, or -1 beyond the dimension.
  int velocity(int axis) const { return axis < dimension() ? axis : -1; }
  int stress_count() const { return kinematics_->stress_count(); }
  /// Field of carried stress component c (the kinematics' order).
  int stress_component(int c) const { return dimension() + c; }
  /// Field of stress component (i, j), or -1 if it is not carried.
  int stress(int i, int j) const;
  /// Field of the pore pressure, or -1 in a dry model.
  int pore_pressure() const { return pore_pressure_; }
  /// Gradient field of field f along axis a.
  int gradient(int field, int axis) const { return field * dimension() + axis; }

 private:
  const KinematicAssumption* kinematics_;
  int pore_pressure_ = -1;
  std::vector<std::string> names_;
  std::vector<Parity> parities_;
};

}  // namespace rktsph
