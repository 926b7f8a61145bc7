// Preconditioned conjugate gradients for a symmetric positive (semi-)definite system
// (docs/theory.md §6.7). It stops when |b - A x| <= tolerance |b|, the criterion of Eigen's
// ConjugateGradient, so that the preconditioners are interchangeable. The vectors are kept between
// solves: a solve allocates nothing.
#pragma once

#include <cstddef>
#include <vector>

#include "rktsph/linear_algebra/preconditioner.hpp"
#include "rktsph/linear_algebra/sparse_rows.hpp"

namespace rktsph {

struct ConjugateGradientResult {
  long iterations = 0;
  double relative_residual = 0.0;  ///< |b - A x| / |b| at exit (0 for b = 0)
  bool converged = false;
};

class ConjugateGradient {
 public:
  explicit ConjugateGradient(std::size_t rows);
  /// Solves A x = b from the guess in x; x is overwritten with the iterate at exit.
  ConjugateGradientResult solve(const SparseRows& a, const Preconditioner& preconditioner,
                                const double* b, double* x, double tolerance, long max_iterations);

 private:
  std::vector<double> residual_, direction_, preconditioned_, product_;
};

}  // namespace rktsph
