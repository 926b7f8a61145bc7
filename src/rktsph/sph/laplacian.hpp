// The SPH Laplacian of the pore-pressure equation (docs/theory.md §6.3): Morris et al. (1997)
//   (L p)_I = c * sum_J 2 V_J (x_I - x_J).grad_I W_IJ / (r_IJ^2 + eta^2) (p_I - p_J),
// eta = 0.1 h, with mirror images of J folded in (pore pressure is even under reflection), and a
// consistency scale c chosen so that L(|x|^2) = 2d on a full interior stencil (docs/theory.md §6.3,
// §7.2: without it the operator is 21 % (1D) / 26 % (2D) too weak at h = 0.75 dx).
//
// The matrix returned is the symmetric Ltilde = diag(V_eff) L, negative semi-definite, where
// V_eff is the node volume halved once per mirror plane the node lies on (docs/theory.md §7.2: the
// node on the plane stands for both halves of the mirrored domain; without the halving Ltilde is
// not symmetric and conjugate gradients fail).
#pragma once

#include <Eigen/SparseCore>
#include <vector>

#include "rktsph/core/point_cloud.hpp"
#include "rktsph/sph/operators.hpp"

namespace rktsph {

struct LaplacianMatrix {
  Eigen::SparseMatrix<double, Eigen::RowMajor> weighted;  ///< Ltilde = diag(V_eff) L
  std::vector<double> effective_volume;                   ///< V_eff per node
  double scale = 1.0;                                     ///< consistency factor c
};

/// c such that L(|x|^2) = 2d on a complete lattice stencil of spacing `spacing` (computed from the
/// kernel on the infinite lattice, so it is one number and keeps the matrix symmetric).
double laplacian_consistency_scale(const Kernel& kernel, double smoothing_length, double spacing,
                                   int dimension);

/// -lambda, lambda the eigenvalue of L (scale included) for the lattice checkerboard (-1)^(i+j+k)
/// on a complete stencil: c sum_J V_J |pair factor| (1 - (-1)^(i_J+j_J+k_J)). Sets the strength of
/// the pore-pressure checkerboard stabilisation (docs/theory.md §6.6).
double laplacian_checkerboard_rate(const Kernel& kernel, double smoothing_length, double spacing,
                                   int dimension, double scale);

/// Assembles Ltilde on `points` (their own neighbours, mirror images included). `scale` <= 0 means
/// the consistency scale above.
LaplacianMatrix build_laplacian(const PointCloud& points, const CellList& cells,
                                const OperatorOptions& options, double spacing, double scale);

}  // namespace rktsph
