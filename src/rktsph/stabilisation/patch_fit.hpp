// The first-order fit of a stress-point field over each node's patch of cells, for the patch
// strain stiffness (docs/theory.md §3.4, eqs. 3.12-3.13).
//
// Node n's patch is the cells it is a corner of; cell P weighs c_Pn = V_P / k_P in it (k_P
// corners), as in the lumped nodal average. A field s (one value per stress point) is fitted on
// each patch by weighted least squares with the linear functions around the node,
//   f_n(x) = a_n + b_n . (x - x_n),                                                     (3.13)
// and the residual of cell P is its value less the mean of its corners' fits at its centroid,
//   rho_P = s_P - sum_{n in P} f_n(x_P) / k_P.
// A field linear in space leaves every residual zero, at the surface and on uneven patches too,
// which the patch mean (a_n alone) does not: there a linear field leaves residuals of the order of
// its gradient times the patch's offset, and a stiffness on them carries load (the measurement of
// §3.4). On a node on a mirror plane the fit is the one of the whole mirrored patch: the functions
// whose parity across the plane differs from the field's are left out (an even field has no slope
// across the plane, an odd one is zero on it). A patch too small or too flat for a slope (fewer
// than three cells off one line) is fitted by what it determines (pseudo-inverse), so a fit is
// always a projection and the residual always the gradient of the energy
//   E = (1/2) sum_n sum_{P in n} c_Pn |s_P - f_n(x_P)|^2.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rktsph/core/field_array.hpp"
#include "rktsph/core/point_cloud.hpp"
#include "rktsph/mesh/cell_complex.hpp"
#include "rktsph/sph/operators.hpp"

namespace rktsph {

class PatchFit {
 public:
  static constexpr std::size_t kMaxFields = 4;
  PatchFit() = default;
  /// Patches of `cells` on the nodes `nodes` with the stress points `points` (positions and
  /// volumes; 2D); `mirror_axes[n]` has bit a set when node n lies on a mirror plane normal to a;
  /// `parity` the parity of each field the fit will be given (at most kMaxFields fields).
  PatchFit(const CellComplex& cells, const PointCloud& nodes, const PointCloud& points,
           std::span<const std::uint8_t> mirror_axes, std::span<const Parity> parity);

  /// residual(f, P) = rho_P of field f of `values` (one value per stress point), eq. 3.13.
  void residual(const FieldArray& values, FieldArray& residual) const;

 private:
  // The linear functions (1, x - x_n, y - y_n) at stress point p seen from node n.
  std::array<double, 3> basis(std::size_t node, std::size_t point) const;

  const CellComplex* cells_ = nullptr;
  const PointCloud* nodes_ = nullptr;
  const PointCloud* points_ = nullptr;
  std::vector<Parity> field_parity_;
  std::vector<Parity> class_parity_;      // the distinct parities among the fields
  std::vector<std::size_t> field_class_;  // each field's place in class_parity_
  // Per node and parity class, the pseudo-inverse of the patch's normal matrix on the functions
  // that class may use (the others' rows and columns zero), row-major 3 x 3.
  std::vector<std::array<double, 9>> inverse_normal_;
  // (a, b_x, b_y) of each field's fit, node by node (a cell reads its corners' whole rows).
  mutable std::vector<std::array<double, 3 * kMaxFields>> coefficient_;
};

}  // namespace rktsph
