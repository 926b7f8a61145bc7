#include "rktsph/linear_algebra/sparse_rows.hpp"

#include <cstdint>

#include "rktsph/core/parallel.hpp"

namespace rktsph {

namespace {

double row_product(const SparseRows& a, std::int64_t row, const double* x) {
  const int* column = a.innerIndexPtr();
  const double* value = a.valuePtr();
  double sum = 0.0;
  for (int k = a.outerIndexPtr()[row]; k < a.outerIndexPtr()[row + 1]; ++k)
    sum += value[k] * x[column[k]];
  return sum;
}
}  // namespace

void multiply(const SparseRows& a, const double* x, double* y) {
  const std::int64_t rows = a.rows();
#pragma omp parallel for schedule(static) if (rows > kParallelThreshold)
  for (std::int64_t i = 0; i < rows; ++i)
    y[i] = row_product(a, i, x);
}

void add_product(const SparseRows& a, const double* x, double* y) {
  const std::int64_t rows = a.rows();
#pragma omp parallel for schedule(static) if (rows > kParallelThreshold)
  for (std::int64_t i = 0; i < rows; ++i)
    y[i] += row_product(a, i, x);
}

void residual(const SparseRows& a, const double* x, const double* b, double* r) {
  const std::int64_t rows = a.rows();
#pragma omp parallel for schedule(static) if (rows > kParallelThreshold)
  for (std::int64_t i = 0; i < rows; ++i)
    r[i] = b[i] - row_product(a, i, x);
}

double dot(const double* x, const double* y, std::size_t n) {
  return chunked_sum(n, [x, y](std::int64_t begin, std::int64_t end) {
    double sum = 0.0;
    for (std::int64_t i = begin; i < end; ++i)
      sum += x[i] * y[i];
    return sum;
  });
}

std::vector<double> diagonal(const SparseRows& a) {
  std::vector<double> result(static_cast<std::size_t>(a.rows()), 0.0);
  for (Eigen::Index i = 0; i < a.outerSize(); ++i)
    for (SparseRows::InnerIterator it(a, i); it; ++it)
      if (it.col() == i) result[static_cast<std::size_t>(i)] += it.value();
  return result;
}

}  // namespace rktsph
