// Sparse matrices stored by rows and the vector kernels of the iterative pressure solve
// (docs/theory.md §6.7). Rows are independent, so the products split over the threads; the sums
// over all entries (dot products) are taken in fixed blocks and added in block order, so a solve
// gives the same bits whatever the number of threads.
#pragma once

#include <Eigen/SparseCore>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rktsph/core/parallel.hpp"

namespace rktsph {

using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

/// y = A x. A must be compressed; x and y must not overlap.
void multiply(const SparseRows& a, const double* x, double* y);

/// y += A x.
void add_product(const SparseRows& a, const double* x, double* y);

/// r = b - A x; r may be b (each row reads its own b before writing it), not x.
void residual(const SparseRows& a, const double* x, const double* b, double* r);

/// sum over c of chunk_sum(begin_c, end_c) over 64 contiguous chunks of [0, n) whose bounds depend
/// on n alone, added in chunk order: the result does not depend on the number of threads, and
/// nothing is allocated. chunk_sum may also write the rows of its chunk (fused updates).
template <typename ChunkSum>
double chunked_sum(std::size_t n, ChunkSum chunk_sum) {
  constexpr std::int64_t chunks = 64;
  const auto length = static_cast<std::int64_t>(n);
  std::array<double, chunks> partial{};
#pragma omp parallel for schedule(static) if (length > kParallelThreshold)
  for (std::int64_t c = 0; c < chunks; ++c)
    partial[static_cast<std::size_t>(c)] =
        chunk_sum(length * c / chunks, length * (c + 1) / chunks);
  double sum = 0.0;
  for (double value : partial)
    sum += value;
  return sum;
}

/// sum_i x_i y_i, by chunked_sum.
double dot(const double* x, const double* y, std::size_t n);

/// The diagonal of A (zero where a row has no diagonal entry).
std::vector<double> diagonal(const SparseRows& a);

}  // namespace rktsph
