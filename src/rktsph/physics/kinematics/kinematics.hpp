// A kinematic setting of the small-strain solid (docs/theory.md §1.2, §1.6): its dimension, the
// stress components it carries, and its elastic stiffness restricted to them. The settings are
// data, one per file (bar_1d.cpp, plane_strain.cpp, plane_stress.cpp); the models read them once
// into tables, so no step loop asks a setting anything per point.
#pragma once

#include <array>
#include <span>
#include <string>

#include "rktsph/physics/kinematics/elastic_stiffness.hpp"

namespace rktsph {

/// The selector the case file and the models use.
enum class Kinematics { Bar1D, PlaneStrain, PlaneStress };

/// Component (i, j) of a symmetric tensor, i <= j.
struct TensorComponent {
  int i = 0, j = 0;
};

/// Slot of component (i, j) in SymmetricTensor order (xx, yy, zz, xy, yz, zx).
int symmetric_tensor_slot(int i, int j);

/// One term of a strain rate: the velocity gradient dv_velocity/dx_axis.
struct VelocityGradientTerm {
  int velocity = 0, axis = 0;
};

/// The engineering strain rate of a component as a sum of velocity-gradient terms: dv_i/dx_i on
/// the diagonal, dv_i/dx_j + dv_j/dx_i off it; terms along axes beyond the dimension vanish.
struct StrainRateTerms {
  int count = 0;
  std::array<VelocityGradientTerm, 2> term{};
};

class KinematicAssumption {
 public:
  static constexpr int kMaxStress = 6;

  /// `carried`: the stress components the model advances; `stress_free`: the components whose
  /// stress vanishes (their strain follows from the others by condensation). Components in
  /// neither list have zero strain and are not carried (sigma_yz, sigma_zx in plane strain).
  KinematicAssumption(int dimension, std::span<const TensorComponent> carried,
                      std::span<const TensorComponent> stress_free);

  int dimension() const { return dimension_; }
  int stress_count() const { return stress_count_; }
  TensorComponent stress_component(int c) const { return carried_[static_cast<std::size_t>(c)]; }
  /// SymmetricTensor slot of carried component c.
  int stress_slot(int c) const;
  /// Index of component (i, j) among the carried ones, or -1.
  int carried_index(int i, int j) const;
  /// "stress_xy" for carried component c.
  std::string stress_name(int c) const;
  /// Engineering strain rate of carried component c from the velocity gradient.
  StrainRateTerms strain_rate_terms(int c) const;
  /// The elastic stiffness on the carried components (engineering shear strains): the 3D
  /// elastic_stiffness with the stress-free components condensed out.
  StiffnessMatrix stiffness(const ElasticConstants& elastic) const;

 private:
  int dimension_;
  int stress_count_ = 0, stress_free_count_ = 0;
  std::array<TensorComponent, kMaxStress> carried_{};
  std::array<TensorComponent, kMaxStress> stress_free_{};
};

/// Uniaxial stress along x: sigma_xx only; the lateral stresses vanish.
const KinematicAssumption& bar_1d();
/// Plane strain in x-y: eps_zz = 0, sigma_zz carried (the invariants need it,
/// docs/theory.md §7.4).
const KinematicAssumption& plane_strain();
/// Plane stress in x-y: sigma_zz = sigma_yz = sigma_zx = 0.
const KinematicAssumption& plane_stress();
const KinematicAssumption& kinematic_assumption(Kinematics kinematics);

}  // namespace rktsph
