#include "rktsph/physics/kinematics/kinematics.hpp"

#include <algorithm>
#include <cassert>

namespace rktsph {

namespace {
const char* axis_name(int axis) {
  return axis == 0 ? "x" : (axis == 1 ? "y" : "z");
}
}  // namespace

int symmetric_tensor_slot(int i, int j) {
  if (i == j) return i;
  const int low = std::min(i, j), high = std::max(i, j);
  if (low == 0 && high == 1) return 3;
  if (low == 1 && high == 2) return 4;
  return 5;
}

KinematicAssumption::KinematicAssumption(int dimension, std::span<const TensorComponent> carried,
                                         std::span<const TensorComponent> stress_free)
    : dimension_(dimension),
      stress_count_(static_cast<int>(carried.size())),
      stress_free_count_(static_cast<int>(stress_free.size())) {
  assert(carried.size() + stress_free.size() <= kMaxStress);
  std::copy(carried.begin(), carried.end(), carried_.begin());
  std::copy(stress_free.begin(), stress_free.end(), stress_free_.begin());
}

int KinematicAssumption::stress_slot(int c) const {
  const TensorComponent component = stress_component(c);
  return symmetric_tensor_slot(component.i, component.j);
}

int KinematicAssumption::carried_index(int i, int j) const {
  const int slot = symmetric_tensor_slot(i, j);
  for (int c = 0; c < stress_count_; ++c)
    if (stress_slot(c) == slot) return c;
  return -1;
}

std::string KinematicAssumption::stress_name(int c) const {
  const TensorComponent component = stress_component(c);
  return std::string("stress_") + axis_name(component.i) + axis_name(component.j);
}

StrainRateTerms KinematicAssumption::strain_rate_terms(int c) const {
  const TensorComponent component = stress_component(c);
  StrainRateTerms terms;
  if (component.i >= dimension_ || component.j >= dimension_) return terms;
  terms.term[static_cast<std::size_t>(terms.count++)] = {component.i, component.j};
  if (component.i != component.j)
    terms.term[static_cast<std::size_t>(terms.count++)] = {component.j, component.i};
  return terms;
}

StiffnessMatrix KinematicAssumption::stiffness(const ElasticConstants& elastic) const {
  std::array<int, kMaxStress> kept{}, free{};
  for (int c = 0; c < stress_count_; ++c)
    kept[static_cast<std::size_t>(c)] = stress_slot(c);
  for (int c = 0; c < stress_free_count_; ++c) {
    const TensorComponent component = stress_free_[static_cast<std::size_t>(c)];
    free[static_cast<std::size_t>(c)] = symmetric_tensor_slot(component.i, component.j);
  }
  return condensed_stiffness(
      elastic_stiffness(elastic),
      std::span<const int>(kept.data(), static_cast<std::size_t>(stress_count_)),
      std::span<const int>(free.data(), static_cast<std::size_t>(stress_free_count_)));
}

const KinematicAssumption& kinematic_assumption(Kinematics kinematics) {
  switch (kinematics) {
    case Kinematics::Bar1D:
      return bar_1d();
    case Kinematics::PlaneStrain:
      return plane_strain();
    case Kinematics::PlaneStress:
      return plane_stress();
  }
  return plane_strain();
}

}  // namespace rktsph
