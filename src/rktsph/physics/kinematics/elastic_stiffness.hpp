// The elastic stiffness of the code, written once: isotropic Hooke's law in 3D (docs/theory.md
// eq. 1.2), and the static condensation that turns it into the stiffness of a kinematic setting
// (docs/theory.md §1.6). Every stiffness the models and the stabilisation use comes from here.
//
// Components are in SymmetricTensor order (xx, yy, zz, xy, yz, zx); the matrix acts on
// engineering shear strains (gamma_xy = 2 eps_xy), which keeps it symmetric: sigma = D gamma.
#pragma once

#include <array>
#include <span>

#include "rktsph/materials/material.hpp"

namespace rktsph {

/// A square stiffness matrix of at most 6 x 6 components, stored without allocation.
class StiffnessMatrix {
 public:
  static constexpr int kMax = 6;

  StiffnessMatrix() = default;
  explicit StiffnessMatrix(int size) : size_(size) {}

  int size() const { return size_; }
  double operator()(int row, int column) const { return entries_[index(row, column)]; }
  double& operator()(int row, int column) { return entries_[index(row, column)]; }

  /// stress = D gamma, each row summed in component order (the step's hot loops call this).
  void multiply(const double* strain, double* stress) const {
    for (int r = 0; r < size_; ++r) {
      double sum = (*this)(r, 0) * strain[0];
      for (int c = 1; c < size_; ++c)
        sum += (*this)(r, c) * strain[c];
      stress[r] = sum;
    }
  }

 private:
  static std::size_t index(int row, int column) {
    return static_cast<std::size_t>(row * kMax + column);
  }

  int size_ = 0;
  std::array<double, kMax * kMax> entries_{};
};

/// D of the isotropic elastic solid: lambda + 2G on the diagonal of the normal block, lambda off
/// it, G on the shear diagonal (engineering shear strains).
StiffnessMatrix elastic_stiffness(const ElasticConstants& elastic);

/// The stiffness of the `kept` components when the stresses of the `stress_free` components vanish
/// (their strains adjust): the Schur complement of the stress-free block, taken one component at a
/// time. Components in neither list are dropped (their strain is held at zero). Row and column k
/// of the result belong to kept[k].
StiffnessMatrix condensed_stiffness(const StiffnessMatrix& full, std::span<const int> kept,
                                    std::span<const int> stress_free);

/// The compliance D^-1 of a stiffness (symmetric positive definite, so Gauss-Jordan elimination
/// needs no pivoting): gamma = D^-1 sigma, engineering shear strains as in D.
StiffnessMatrix compliance(const StiffnessMatrix& stiffness);

}  // namespace rktsph
