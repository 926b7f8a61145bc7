// Sparse matrices stored by rows and the vector kernels of the iterative pressure solve
// (docs/theory.md §6.7). Rows are independent, so the products split over the threads; the sums
// over all entries (dot products) are taken in fixed blocks and added in block order, so a solve
// gives the same bits whatever the number of threads.
#pragma once

#include <Eigen/SparseCore>
#include <cstddef>
#include <vector>

namespace rktsph {

using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

/// y = A x. A must be compressed; x and y must not overlap.
void multiply(const SparseRows& a, const double* x, double* y);

/// r = b - A x.
void residual(const SparseRows& a, const double* x, const double* b, double* r);

/// sum_i x_i y_i, in fixed blocks independent of the number of threads.
double dot(const double* x, const double* y, std::size_t n);

/// The diagonal of A (zero where a row has no diagonal entry).
std::vector<double> diagonal(const SparseRows& a);

}  // namespace rktsph
