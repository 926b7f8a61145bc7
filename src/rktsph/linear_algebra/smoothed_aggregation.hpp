// Smoothed-aggregation algebraic multigrid (Vanek, Mandel and Brezina 1996) as the preconditioner
// of the pore-pressure solve (docs/theory.md §6.7). Setup, once per matrix: the strong couplings
// |a_ij| >= eps sqrt(a_ii a_jj) group the unknowns into aggregates (eps halved on each coarser
// level); the piecewise-constant prolongator is smoothed by one damped Jacobi step,
// P = (I - 4/(3 lambda) D^-1 A) P0, and the coarse matrix is P^T A P, down to a few hundred
// unknowns factored once (sparse LDL^T). Apply: one V-cycle from a zero guess, a forward
// Gauss-Seidel sweep before the coarse correction and the backward sweep after it, which makes the
// cycle a symmetric positive-definite operator, as conjugate gradients need. The sweeps run in
// fixed chunks of rows (Gauss-Seidel within a chunk, Jacobi between chunks) so that they split over
// the threads and give the same bits for any number of threads; the cycle allocates nothing.
#pragma once

#include <Eigen/SparseCholesky>
#include <cstddef>
#include <vector>

#include "rktsph/linear_algebra/preconditioner.hpp"
#include "rktsph/linear_algebra/sparse_rows.hpp"

namespace rktsph {

struct MultigridOptions {
  double strength_threshold = 0.08;  ///< eps on the finest level (Vanek et al.'s value)
  std::size_t coarsest_rows = 300;   ///< factored at or below this size
  int max_levels = 12;
};

class SmoothedAggregation final : public Preconditioner {
 public:
  /// Builds the hierarchy of `a` (symmetric positive definite, compressed, sorted rows with a
  /// diagonal entry each); `a` must outlive this object.
  explicit SmoothedAggregation(const SparseRows& a, const MultigridOptions& options = {});
  void apply(const double* r, double* z) const override;

  std::size_t levels() const { return levels_.size(); }
  std::size_t rows(std::size_t level) const;
  /// sum over levels of the matrix entries, over those of the finest matrix.
  double operator_complexity() const;

 private:
  struct Level {
    const SparseRows* matrix = nullptr;  // the finest level points to the caller's matrix
    SparseRows coarse_matrix;            // owned on coarser levels
    SparseRows prolongator;              // from the next coarser level to this one
    SparseRows restriction;              // P^T, stored so that both are products over rows
    std::vector<double> inverse_diagonal;
    std::vector<int> diagonal_entry;  // index of each row's diagonal among the entries
    // Workspace of the cycle (rhs and solution stay empty on the finest level: apply's r and z).
    mutable std::vector<double> rhs, solution, residual, snapshot;
  };

  /// x = the V-cycle from `level` down applied to b.
  void cycle(std::size_t level, const double* b, double* x) const;
  /// The forward sweep from a zero guess, leaving b - A x in level.residual.
  void forward_gauss_seidel(const Level& level, const double* b, double* x) const;
  /// The backward sweep from the current x (the adjoint of the forward one).
  void backward_gauss_seidel(const Level& level, const double* b, double* x) const;

  MultigridOptions options_;
  std::vector<Level> levels_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> coarsest_;
};

/// The aggregate of each row from the strong couplings of `a` (-1 for a row with none: it is
/// left to the smoother); `count` receives the number of aggregates. Exposed for tests.
std::vector<int> aggregate_rows(const SparseRows& a, double strength_threshold, int* count);

/// An upper bound on the spectrum of D^-1 A for symmetric A with a positive diagonal: 1.1 times a
/// Rayleigh-quotient power estimate, never above the row-sum (Gershgorin) bound.
double estimate_upper_eigenvalue(const SparseRows& a, const std::vector<double>& inverse_diagonal);

}  // namespace rktsph
