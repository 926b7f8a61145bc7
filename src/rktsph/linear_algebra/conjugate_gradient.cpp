#include "rktsph/linear_algebra/conjugate_gradient.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "rktsph/core/parallel.hpp"

namespace rktsph {

ConjugateGradient::ConjugateGradient(std::size_t rows)
    : residual_(rows), direction_(rows), preconditioned_(rows), product_(rows) {}

ConjugateGradientResult ConjugateGradient::solve(const SparseRows& a,
                                                 const Preconditioner& preconditioner,
                                                 const double* b, double* x, double tolerance,
                                                 long max_iterations) {
  const std::size_t n = residual_.size();
  if (static_cast<std::size_t>(a.rows()) != n || static_cast<std::size_t>(a.cols()) != n)
    throw std::invalid_argument("ConjugateGradient: the matrix does not match the workspace");
  const auto rows = static_cast<std::int64_t>(n);
  double* r = residual_.data();
  double* p = direction_.data();
  double* z = preconditioned_.data();
  double* q = product_.data();
  ConjugateGradientResult result;
  const double rhs_norm2 = dot(b, b, n);
  if (rhs_norm2 == 0.0) {
    parallel_fill(x, n, 0.0);
    result.converged = true;
    return result;
  }
  const double threshold = tolerance * tolerance * rhs_norm2;
  residual(a, x, b, r);
  double residual_norm2 = dot(r, r, n);
  if (residual_norm2 < threshold) {
    result.relative_residual = std::sqrt(residual_norm2 / rhs_norm2);
    result.converged = true;
    return result;
  }
  preconditioner.apply(r, z);
  parallel_copy(z, n, p);
  double rz = dot(r, z, n);
  while (result.iterations < max_iterations) {
    multiply(a, p, q);
    const double alpha = rz / dot(p, q, n);
    // x += alpha p, r -= alpha q and |r|^2 in one pass.
    residual_norm2 = chunked_sum(n, [=](std::int64_t begin, std::int64_t end) {
      double sum = 0.0;
      for (std::int64_t i = begin; i < end; ++i) {
        x[i] += alpha * p[i];
        r[i] -= alpha * q[i];
        sum += r[i] * r[i];
      }
      return sum;
    });
    ++result.iterations;
    if (!std::isfinite(residual_norm2) || residual_norm2 < threshold) break;
    preconditioner.apply(r, z);
    const double rz_next = dot(r, z, n);
    const double beta = rz_next / rz;
    rz = rz_next;
#pragma omp parallel for schedule(static) if (rows > kParallelThreshold)
    for (std::int64_t i = 0; i < rows; ++i)
      p[i] = z[i] + beta * p[i];
  }
  result.relative_residual = std::sqrt(residual_norm2 / rhs_norm2);
  result.converged = std::isfinite(residual_norm2) && residual_norm2 < threshold;
  return result;
}

}  // namespace rktsph
